#!/usr/bin/python3
"""The beam experiment's images (beam_experiment: points.exr, beams.exr) against a reference, in the
beam regions of bench/convergence/media_scenes_regions.json: relMSE (kasha.metrics) and the ratio of
the region's mean Y to the reference's (the estimators' bias shows there).

    region_errors.py REFERENCE.exr DIR [DIR ...]
"""
import importlib.util
import json
import os
import statistics
import sys

if importlib.util.find_spec("numpy") is None:
    # A Python without numpy first on PATH (pyenv, a venv): use Debian's (python3-numpy).
    if os.path.realpath(sys.executable) != os.path.realpath("/usr/bin/python3") and os.path.exists("/usr/bin/python3"):
        os.execv("/usr/bin/python3", ["/usr/bin/python3"] + sys.argv)
    sys.exit("region_errors.py: error: needs numpy (Debian: python3-numpy)")

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(os.path.dirname(HERE))
sys.path.insert(0, os.path.join(REPO, "build", "python"))
import kasha  # noqa: E402
import numpy as np  # noqa: E402


def main():
    if len(sys.argv) < 3:
        print(__doc__, file=sys.stderr)
        return 2
    with open(os.path.join(REPO, "bench", "convergence", "media_scenes_regions.json")) as f:
        boxes = {k: v for k, v in json.load(f)["uv_dye_caustic"].items() if k.startswith("beam")}
    ref = np.asarray(kasha.read_exr(sys.argv[1])["xyz"])
    h, w = ref.shape[:2]
    rows = {}
    for d in sys.argv[2:]:
        for name in ("points", "beams"):
            img = np.asarray(kasha.read_exr(os.path.join(d, name + ".exr"))["xyz"])
            for region, (x0, y0, x1, y1) in boxes.items():
                ys, xs = slice(int(y0 * h), int(y1 * h)), slice(int(x0 * w), int(x1 * w))
                err = kasha.metrics(img[ys, xs].copy(), ref[ys, xs].copy())["relmse"]
                ratio = float(img[ys, xs, 1].mean() / ref[ys, xs, 1].mean())
                rows.setdefault((name, region), []).append((err, ratio))
    print("| estimator | region | relMSE (mean over runs) | mean Y / reference's |")
    print("|---|---|---|---|")
    for (name, region), v in sorted(rows.items()):
        errs, ratios = [e for e, _ in v], [r for _, r in v]
        print(f"| {name} | {region} | {statistics.mean(errs):.3g} | {statistics.mean(ratios):.3f} |")
    return 0


if __name__ == "__main__":
    sys.exit(main())
