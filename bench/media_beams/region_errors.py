#!/usr/bin/python3
"""The beam experiment's images (beam_experiment: points.exr, pointbeam.exr, beams.exr) against a
reference, in the regions of SCENE in bench/convergence/media_scenes_regions.json: relMSE
(kasha.metrics), the relative variance over the runs, and the ratio of the region's mean Y to the
reference's (the estimators' bias, or the share of the region's light they render: one event on
the camera's first segment through the medium).

    region_errors.py SCENE REFERENCE.exr DIR [DIR ...]
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
    if len(sys.argv) < 4:
        print(__doc__, file=sys.stderr)
        return 2
    with open(os.path.join(REPO, "bench", "convergence", "media_scenes_regions.json")) as f:
        boxes = json.load(f)[sys.argv[1]]
    ref = np.asarray(kasha.read_exr(sys.argv[2])["xyz"])
    h, w = ref.shape[:2]
    rows = {}
    for name in ("points", "pointbeam", "beams"):
        images = [np.asarray(kasha.read_exr(os.path.join(d, name + ".exr"))["xyz"]) for d in sys.argv[3:]]
        for region, (x0, y0, x1, y1) in boxes.items():
            ys, xs = slice(int(y0 * h), int(y1 * h)), slice(int(x0 * w), int(x1 * w))
            errs = [kasha.metrics(img[ys, xs].copy(), ref[ys, xs].copy())["relmse"] for img in images]
            luminance = np.stack([img[ys, xs, 1] for img in images])
            ratio = float(luminance.mean() / ref[ys, xs, 1].mean())
            if ratio < 0.01:  # light of other paths (a floor, a wall): not the experiment's
                continue
            # The noise alone: the variance over the runs of each pixel, over the region's mean
            # squared (reference).
            noise = float(luminance.var(axis=0, ddof=1).mean() / ref[ys, xs, 1].mean() ** 2)
            rows[(name, region)] = (statistics.mean(errs), noise, ratio)
    print("| estimator | region | relMSE (mean over runs) | relative variance over runs | mean Y / reference's |")
    print("|---|---|---|---|---|")
    for (name, region), (err, noise, ratio) in sorted(rows.items()):
        print(f"| {name} | {region} | {err:.3g} | {noise:.3g} | {ratio:.3f} |")
    return 0


if __name__ == "__main__":
    sys.exit(main())
