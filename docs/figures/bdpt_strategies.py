#!/usr/bin/env python3
"""Renders scenes/cornell_uv.json at 128x128 with `kasha render --strategy-images` and composes
the MIS-weighted per-strategy PNGs into one labelled grid, docs/figures/bdpt_strategies.png.

Usage (from the repository root, after building): python3 docs/figures/bdpt_strategies.py [build/kasha]
Row d holds the paths with d scattering events; column s the strategies with s light-subpath
vertices (t = d + 2 - s >= 1 camera-subpath vertices, the pinhole included); then the s = 1
strategy through the light subpath's own vertex (its wavelength bridged by a fluorescent lobe),
the full image and the paths longer than DEPTH. One exposure for all, so brightness compares."""
import json
import os
import subprocess
import sys
import tempfile

import matplotlib
matplotlib.use("Agg")
import matplotlib.image as mpimg
import matplotlib.pyplot as plt

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
KASHA = sys.argv[1] if len(sys.argv) > 1 else os.path.join(ROOT, "build", "kasha")
SCENE = os.path.join(ROOT, "scenes", "cornell_uv.json")
OUT = os.path.join(ROOT, "docs", "figures", "bdpt_strategies.png")
DEPTH, SPP, SIZE, EXPOSURE = 3, 64, 128, 2.0


def small_scene(tmp):
    """The scene at SIZE x SIZE with its spectrum files resolved against the original folder."""
    with open(SCENE) as f:
        scene = json.load(f)
    scene["camera"]["resolution"] = [SIZE, SIZE]
    for spec in scene.get("spectra", {}).values():
        if isinstance(spec, dict) and "file" in spec:
            spec["file"] = os.path.join(os.path.dirname(SCENE), spec["file"])
    path = os.path.join(tmp, "cornell_uv_small.json")
    with open(path, "w") as f:
        json.dump(scene, f)
    return path


def main():
    with tempfile.TemporaryDirectory() as tmp:
        images = os.path.join(tmp, "strategies")
        cmd = [KASHA, "render", small_scene(tmp), "--integrator", "bdpt-independent", "--spp", str(SPP), "--seed", "1",
               "--exposure", str(EXPOSURE), "--strategy-images", images, "--strategy-depth", str(DEPTH),
               "-o", os.path.join(tmp, "full.exr"), "-q"]
        print(" ".join(cmd[:1] + ["render", "<cornell_uv at %dx%d>" % (SIZE, SIZE)] + cmd[3:]))
        subprocess.run(cmd, check=True)
        cols = DEPTH + 3  # s = 0 ... DEPTH + 1, and the light-vertex variant of s = 1
        fig, axes = plt.subplots(DEPTH + 1, cols + 1, figsize=(1.6 * (cols + 1), 1.7 * (DEPTH + 1)))
        for ax in axes.flat:
            ax.axis("off")
        full = mpimg.imread(os.path.join(tmp, "full.png"))
        axes[0][cols].imshow(full)
        axes[0][cols].set_title("full image", fontsize=8)
        deeper = os.path.join(images, "deeper.png")
        if os.path.exists(deeper):
            axes[1][cols].imshow(mpimg.imread(deeper))
            axes[1][cols].set_title("> %d events" % DEPTH, fontsize=8)
        for d in range(DEPTH + 1):
            for s in range(d + 2):
                t = d + 2 - s
                # s = 0 and next-event estimation are the camera's; joins and t = 1 the own family's.
                png = os.path.join(images, "s%d_t%d%s.png" % (s, t, "" if s <= 1 and t >= 2 else "_own"))
                if os.path.exists(png):
                    axes[d][s].imshow(mpimg.imread(png))
                axes[d][s].set_title("s=%d, t=%d" % (s, t), fontsize=8)
            lv = os.path.join(images, "s1_t%d_light_vertex.png" % (d + 1))
            if d >= 1 and os.path.exists(lv):
                axes[d][cols - 1].imshow(mpimg.imread(lv))
                axes[d][cols - 1].set_title("s=1, t=%d, light vertex" % (d + 1), fontsize=7)
            axes[d][0].text(-0.15, 0.5, "%d events" % d, transform=axes[d][0].transAxes, rotation=90, va="center",
                            ha="right", fontsize=8)
        fig.suptitle("BDPT (independent wavelengths) on cornell_uv: MIS-weighted strategies, %d spp" % SPP, fontsize=9)
        fig.tight_layout()
        fig.savefig(OUT, dpi=110)
        print("wrote", OUT)


if __name__ == "__main__":
    main()
