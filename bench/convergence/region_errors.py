#!/usr/bin/python3
"""Per-region errors of a finished convergence run: for each scene of a regions file, the relMSE of
every configuration's renders at the largest budget inside each named region of the image (mean and
standard deviation over seeds), so that a scene where different configurations win in different
places can show it.

    python3 bench/convergence/run.py bench/convergence/vcm_scene.json          # the renders first
    python3 bench/convergence/region_errors.py bench/convergence/vcm_scene.json \
        bench/convergence/vcm_scene_regions.json [--build-dir build]

The regions file maps a scene name of the report file to its regions, each [x0, y0, x1, y1] in
fractions of the image as the report's `crop`: {"uv_caustic_mirror": {"caustic": [0.4, 0.7, 0.6,
0.8], ...}}. The renders and the reference are read from the report's work directory, where run.py
left them; the error is kasha's relMSE (integrators/comparison.h, through the Python module
`kasha`) of the region's pixels alone. Prints a Markdown table, one row per configuration.
"""
import argparse
import json
import os
import statistics
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import config as config_file  # noqa: E402
import kasha_cli  # noqa: E402
import run  # noqa: E402  (re-runs itself with Debian's Python if numpy is missing)


def _pixels(box, shape):
    """The rows and columns of box = [x0, y0, x1, y1] (fractions) in an image of shape (h, w, ...)."""
    h, w = shape[:2]
    x0, y0 = int(box[0] * w), int(box[1] * h)
    return slice(y0, max(y0 + 1, int(box[3] * h))), slice(x0, max(x0 + 1, int(box[2] * w)))


def _load_regions(path, scenes):
    with open(path) as f:
        regions = json.load(f)
    if not isinstance(regions, dict) or not regions:
        raise config_file.ConfigError(f"{path}: expected an object of scenes")
    for name, boxes in regions.items():
        if name not in scenes:
            raise config_file.ConfigError(f"{path}: /{name}: no such scene in the report file")
        if not isinstance(boxes, dict) or not boxes:
            raise config_file.ConfigError(f"{path}: /{name}: expected an object of regions")
        for label, box in boxes.items():
            config_file._crop(path, f"/{name}/{label}", box)
    return regions


def scene_table(kasha, cfg, sc, boxes):
    """Markdown rows: per configuration, relMSE mean ± sd over seeds in each region at the largest budget."""
    work = os.path.join(cfg["work"], sc["name"])
    ref_name = os.path.splitext(os.path.basename(sc["scene"]))[0]
    ref = kasha.read_exr(os.path.join(cfg["work"], "references", ref_name + ".exr"))["xyz"]
    budget = cfg["budget"]["values"][-1]
    names = list(boxes)
    rows, means = [], {}
    for c in sc["configurations"]:
        per = {n: [] for n in names}
        for seed in cfg["seeds"]:
            exr = os.path.join(work, f"{run._safe(c['label'])}_b{budget:g}_s{seed}.exr")
            img = kasha.read_exr(exr)["xyz"]
            for n in names:
                ys, xs = _pixels(boxes[n], img.shape)
                per[n].append(kasha.metrics(img[ys, xs].copy(), ref[ys, xs].copy())["relmse"])
        means[c["label"]] = {n: statistics.mean(v) for n, v in per.items()}
        rows.append((c["label"], {n: (statistics.mean(v), statistics.stdev(v)) for n, v in per.items()}))
    best = {n: min(means, key=lambda label: means[label][n]) for n in names}
    unit = "s" if cfg["budget"]["kind"] == "time" else "spp"
    out = [f"{sc['name']}: relMSE per region at {budget:g} {unit} "
           f"(mean ± sd over seeds {', '.join(map(str, cfg['seeds']))}; **best**)", "",
           "| configuration | " + " | ".join(f"{n} {boxes[n]}" for n in names) + " |",
           "|---|" + "---|" * len(names)]
    for label, stats in rows:
        cells = [f"{m:.3g} ± {s:.2g}" for m, s in (stats[n] for n in names)]
        cells = [f"**{cell}**" if best[n] == label else cell for n, cell in zip(names, cells)]
        out.append(f"| {label} | " + " | ".join(cells) + " |")
    return out


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("config", help="the report configuration run.py rendered (JSON)")
    ap.add_argument("regions", help="regions file (JSON): scene name -> {region: [x0, y0, x1, y1]}")
    ap.add_argument("--build-dir", default=os.path.join(kasha_cli.REPO, "build"), help="where the module kasha is built")
    a = ap.parse_args()
    try:
        cfg = config_file.load(a.config, False)
        scenes = {s["name"]: s for s in cfg["scenes"]}
        regions = _load_regions(a.regions, scenes)
    except (config_file.ConfigError, OSError, json.JSONDecodeError) as e:
        print(f"region_errors.py: error: {e}", file=sys.stderr)
        return 1
    sys.path.insert(0, os.path.join(a.build_dir, "python"))
    import kasha
    try:
        for name, boxes in regions.items():
            print("\n".join(scene_table(kasha, cfg, scenes[name], boxes)) + "\n")
    except (OSError, ValueError) as e:
        print(f"region_errors.py: error: {e} (has run.py rendered {a.config}?)", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
