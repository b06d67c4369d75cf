#!/usr/bin/python3
"""Convergence report: for each scene of a configuration file, render (or reuse) a reference, run
every configuration (label, integrator, extra `kasha render` arguments) at each budget with each
seed, and write runs.csv, summary.csv, plots, crops and report.md into the output directory.

    python3 bench/convergence/run.py bench/convergence/report.json [--quick] [--scene NAME]

See bench/convergence/README.md for the configuration format.
"""
import argparse
import datetime
import importlib.util
import os
import platform
import re
import shlex
import sys
import time

if importlib.util.find_spec("matplotlib") is None or importlib.util.find_spec("numpy") is None:
    # A Python without them first on PATH (pyenv, a venv): use Debian's, which has python3-numpy and
    # python3-matplotlib (.ci/install-deps.sh).
    if os.path.realpath(sys.executable) != os.path.realpath("/usr/bin/python3") and os.path.exists("/usr/bin/python3"):
        os.execv("/usr/bin/python3", ["/usr/bin/python3"] + sys.argv)
    sys.exit("run.py: error: needs numpy and matplotlib (Debian: python3-numpy python3-matplotlib)")

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import config as config_file  # noqa: E402
import kasha_cli  # noqa: E402
import measure  # noqa: E402
import report  # noqa: E402


def _safe(label):
    return re.sub(r"[^A-Za-z0-9_.-]+", "_", label).strip("_")


def _machine():
    model = platform.machine()
    try:
        with open("/proc/cpuinfo") as f:
            model = next((l.split(":", 1)[1].strip() for l in f if l.startswith("model name")), model)
    except OSError:
        pass
    return f"{os.cpu_count()} cores ({model})"


def run_scene(binary, metrics, cfg, sc, runs, log):
    work = os.path.join(cfg["work"], sc["name"])
    os.makedirs(work, exist_ok=True)
    scene = kasha_cli.prepare_scene(sc["scene"], sc["resolution_scale"], os.path.join(work, "scene"))
    ref, ref_stats = kasha_cli.reference(binary, scene, os.path.join(cfg["work"], "references"), sc["reference"],
                                         cfg["threads"], log)
    largest = cfg["budget"]["values"][-1]
    crops = []
    for budget in cfg["budget"]["values"]:
        for seed in cfg["seeds"]:
            for c in sc["configurations"]:
                exr = os.path.join(work, f"{_safe(c['label'])}_b{budget:g}_s{seed}.exr")
                stats = kasha_cli.render(binary, scene, exr, c["integrator"], c["args"], seed,
                                         cfg["budget"]["kind"], budget, cfg["threads"])
                show = budget == largest and seed == cfg["seeds"][0]
                err_map = os.path.splitext(exr)[0] + ".error.pfm" if show else None
                m = metrics(exr, ref, err_map)
                runs.append({"scene": sc["name"], "config": c["label"], "integrator": c["integrator"],
                             "args": " ".join(c["args"]), "budget_kind": cfg["budget"]["kind"], "budget": budget,
                             "seed": seed, "seconds": stats["seconds"], "spp": stats["spp"], "rmse": m["rmse"],
                             "relmse": m["relmse"]})
                if show:
                    crops.append((c["label"], os.path.splitext(exr)[0] + ".png", err_map, m["relmse"]))
                log(f"  {c['label']:<28} budget {budget:<6g} seed {seed}: {stats['seconds']:.2f} s, "
                    f"{stats['spp']} spp, relMSE {m['relmse']:.4g}")
    return {"name": sc["name"], "note": sc["note"], "scene": sc["scene"], "reference": sc["reference"],
            "reference_stats": ref_stats,
            "resolution": ref_stats.get("resolution", [0, 0]), "reference_png": os.path.splitext(ref)[0] + ".png",
            "crops_columns": crops, "crop": sc["crop"], "comparisons": sc["comparisons"]}


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("config", help="report configuration (JSON)")
    ap.add_argument("--quick", action="store_true", help="apply the configuration's `quick` reductions")
    ap.add_argument("--scene", action="append", help="only this scene (by name; repeatable); no report page")
    ap.add_argument("--build-dir", default=os.path.join(kasha_cli.REPO, "build"), help="CMake build directory")
    ap.add_argument("--cli", action="store_true",
                    help="measure errors with `kasha metrics` subprocesses instead of the Python module")
    a = ap.parse_args()
    try:
        cfg = config_file.load(a.config, a.quick)
    except config_file.ConfigError as e:
        print(f"run.py: error: {e}", file=sys.stderr)
        return 1
    cfg["repo"] = kasha_cli.REPO
    scenes = [s for s in cfg["scenes"] if not a.scene or s["name"] in a.scene]
    if a.scene and len(scenes) != len(set(a.scene)):
        print(f"run.py: error: --scene: no such scene in {a.config}", file=sys.stderr)
        return 1
    start = time.time()
    log = lambda msg: print(msg, flush=True)  # noqa: E731
    binary = kasha_cli.build(a.build_dir, with_module=not a.cli)
    metrics, path = measure.metrics_function(binary, a.build_dir, a.cli)
    log(f"errors measured {'in-process by the kasha module' if path == 'module' else 'by kasha metrics'}")
    os.makedirs(cfg["output"], exist_ok=True)
    runs, done = [], []
    try:
        for sc in scenes:
            log(f"{sc['name']}:")
            done.append(run_scene(binary, metrics, cfg, sc, runs, log))
    except (kasha_cli.KashaError, ValueError) as e:
        print(f"run.py: error: {e}", file=sys.stderr)
        return 1
    import figures  # matplotlib takes a while to import: only once there is something to draw

    summary = report.summarise(runs)
    for s in done:
        s["plot"], s["crops"] = s["name"] + "_convergence.png", s["name"] + "_crops.png"
        figures.convergence_plot(summary[s["name"]], cfg["budget"]["kind"], s["name"],
                                 os.path.join(cfg["output"], s["plot"]))
        figures.crops_figure(s["reference_png"], s["crops_columns"], s["crop"],
                             f"{s['name']}: largest budget, seed {cfg['seeds'][0]}",
                             os.path.join(cfg["output"], s["crops"]))
    if a.scene:
        log(f"figures for {', '.join(a.scene)} in {cfg['output']} (no report page for a subset)")
        return 0
    report.write_csv(os.path.join(cfg["output"], "runs.csv"), report.RUN_FIELDS, runs)
    report.write_csv(os.path.join(cfg["output"], "summary.csv"), report.SUMMARY_FIELDS,
                     [r for configs in summary.values() for rows in configs.values() for r in rows])
    command = "python3 " + " ".join(shlex.quote(os.path.relpath(p, kasha_cli.REPO)) if os.path.exists(p) else p
                                    for p in [os.path.abspath(__file__), os.path.abspath(a.config)])
    command += " --quick" if a.quick else ""
    page = report.markdown(cfg, done, summary, command, time.time() - start, _machine(),
                           datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d %H:%M UTC"), runs)
    with open(os.path.join(cfg["output"], "report.md"), "w") as f:
        f.write(page)
    log(f"wrote {os.path.join(cfg['output'], 'report.md')} in {(time.time() - start) / 60:.1f} min")
    return 0


if __name__ == "__main__":
    sys.exit(main())
