"""Running the kasha binary from the harness: building it, preparing scenes, rendering, measuring.

Every render goes through `kasha render` (its statistics JSON gives the actual time and samples per
pixel: configurations are `kasha render` arguments); errors go through `kasha metrics` (the RMSE
and relMSE of integrators/comparison.h) with --cli, otherwise through the module (measure.py).
"""
import hashlib
import json
import os
import subprocess
import sys

REPO = os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", ".."))


class KashaError(Exception):
    pass


def build(build_dir, with_module=False):
    """Configures (once) and builds the kasha target (and the Python module kasha_python) in
    Release; returns the binary's path."""
    env = dict(os.environ, CCACHE_BASEDIR=os.path.dirname(REPO))
    if not os.path.isfile(os.path.join(build_dir, "CMakeCache.txt")):
        subprocess.run(["cmake", "-S", REPO, "-B", build_dir, "-DCMAKE_BUILD_TYPE=Release"], check=True, env=env,
                       stdout=subprocess.DEVNULL)
    targets = ["kasha"] + (["kasha_python"] if with_module and _has_target(build_dir, "kasha_python") else [])
    subprocess.run(["cmake", "--build", build_dir, "-j2", "--target"] + targets, check=True, env=env,
                   stdout=subprocess.DEVNULL)
    return os.path.join(build_dir, "kasha")


def _has_target(build_dir, target):
    """Whether the build directory's configuration has `target` (the module is optional)."""
    p = subprocess.run(["cmake", "--build", build_dir, "--target", "help"], capture_output=True, text=True)
    return target in p.stdout


def _run(cmd):
    p = subprocess.run(cmd, capture_output=True, text=True)
    if p.returncode != 0:
        raise KashaError(f"{' '.join(cmd)}\nexited with {p.returncode}: {p.stderr.strip()}")
    return p.stdout


def _absolute_files(node, base):
    """Spectrum CSV and mesh paths ("file" fields) made absolute, so the scene can move."""
    if isinstance(node, dict):
        return {k: (os.path.join(base, v) if k == "file" and isinstance(v, str) and not os.path.isabs(v)
                    else _absolute_files(v, base)) for k, v in node.items()}
    if isinstance(node, list):
        return [_absolute_files(v, base) for v in node]
    return node


def prepare_scene(scene, resolution_scale, work_dir):
    """The scene to render: the file itself, or a copy at a scaled resolution in work_dir."""
    if resolution_scale == 1.0:
        return scene
    with open(scene) as f:
        j = json.load(f)
    w, h = j["camera"]["resolution"]
    j["camera"]["resolution"] = [max(1, round(w * resolution_scale)), max(1, round(h * resolution_scale))]
    j = _absolute_files(j, os.path.dirname(os.path.abspath(scene)))
    os.makedirs(work_dir, exist_ok=True)
    out = os.path.join(work_dir, os.path.basename(scene))
    with open(out, "w") as f:
        json.dump(j, f, indent=1)
    return out


def render(kasha, scene, out_exr, integrator, args, seed, budget_kind, budget, threads):
    """Renders; returns the statistics JSON (seconds, spp, ...)."""
    budget_args = ["--time", repr(float(budget))] if budget_kind == "time" else ["--spp", str(int(budget))]
    cmd = [kasha, "render", scene, "-q", "-o", out_exr, "--integrator", integrator, "--seed", str(seed),
           "--threads", str(threads)] + budget_args + list(args)
    _run(cmd)
    with open(os.path.splitext(out_exr)[0] + ".stats.json") as f:
        return json.load(f)


def metrics(kasha, image, reference, error_map=None):
    """{"rmse", "relmse", ...} of image against reference (kasha metrics); optionally a PFM error map."""
    cmd = [kasha, "metrics", image, reference] + (["--error-map", error_map] if error_map else [])
    return json.loads(_run(cmd))


def _file_hash(path):
    with open(path, "rb") as f:
        return hashlib.sha256(f.read()).hexdigest()


def reference(kasha, scene, ref_dir, ref_cfg, threads, log=print):
    """The reference EXR for `scene`: reused when its recorded settings (scene text, integrator,
    arguments, time, seed) match, rendered otherwise. Returns (exr path, its statistics)."""
    name = os.path.splitext(os.path.basename(scene))[0]
    exr = os.path.join(ref_dir, name + ".exr")
    key = {"scene_sha256": _file_hash(scene), "integrator": ref_cfg["integrator"], "args": ref_cfg["args"],
           "time": ref_cfg["time"], "seed": ref_cfg["seed"]}
    key_file = os.path.join(ref_dir, name + ".reference.json")
    if os.path.isfile(exr) and os.path.isfile(key_file):
        with open(key_file) as f:
            if json.load(f) == key:
                with open(os.path.join(ref_dir, name + ".stats.json")) as g:
                    log(f"  reference {exr}: reused")
                    return exr, json.load(g)
    os.makedirs(ref_dir, exist_ok=True)
    log(f"  reference {exr}: {ref_cfg['integrator']} for {ref_cfg['time']:g} s ...")
    sys.stdout.flush()
    stats = render(kasha, scene, exr, ref_cfg["integrator"], ref_cfg["args"], ref_cfg["seed"], "time",
                   ref_cfg["time"], threads)
    with open(key_file, "w") as f:
        json.dump(key, f, indent=1)
    return exr, stats
