#!/usr/bin/env python3
"""A contact sheet of kasha's renders of Mitsuba 3's documentation scenes beside Mitsuba's own images.

Issue 35's side-by-side check. Run survey.py first (it writes NAME.png beside NAME.exr in --out and
the results with --json), then

    python3 bench/mitsuba_scenes/contact_sheet.py --survey /tmp/mitsuba_survey.json \
        --renders /tmp/mitsuba_survey --references /path/to/mitsuba-data/docs/images/render \
        --out docs/figures/mitsuba_contact_sheet.jpg

Each row is one scene whose name starts with one of --prefixes: Mitsuba's image (left) and kasha's
render (right), or kasha's first error where it does not render.
"""

import argparse
import json
import os
import textwrap

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
from PIL import Image


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--survey", required=True, help="survey.py --json output")
    parser.add_argument("--renders", required=True, help="survey.py --out folder")
    parser.add_argument("--references", required=True, help="mitsuba-data/docs/images/render")
    parser.add_argument("--prefixes", default="bsdf_,sensor_,emitter_")
    parser.add_argument("--out", required=True)
    args = parser.parse_args()
    with open(args.survey) as f:
        results = json.load(f)
    prefixes = tuple(args.prefixes.split(","))
    rows = [r for r in results if r["scene"].startswith(prefixes)
            and os.path.exists(os.path.join(args.references, r["scene"] + ".jpg"))]
    columns = 4  # two scenes per row: (Mitsuba, kasha) twice
    lines = (len(rows) + 1) // 2
    fig, axes = plt.subplots(lines, columns, figsize=(columns * 2.2, lines * 1.9), squeeze=False)
    for ax in axes.flat:
        ax.axis("off")
    for i, r in enumerate(rows):
        left, right = axes[i // 2][(i % 2) * 2], axes[i // 2][(i % 2) * 2 + 1]
        left.imshow(Image.open(os.path.join(args.references, r["scene"] + ".jpg")))
        left.set_title("Mitsuba: " + r["scene"], fontsize=5)
        png = os.path.join(args.renders, r["scene"] + ".png")
        if r["result"] == "renders" and os.path.exists(png):
            right.imshow(Image.open(png))
            right.set_title("kasha", fontsize=5)
        else:
            reason = r["result"].replace("kasha: error: ", "")
            right.text(0.0, 0.5, "\n".join(textwrap.wrap(reason, 38)[:9]), fontsize=4, va="center", wrap=True)
    fig.tight_layout(pad=0.3)
    fig.savefig(args.out, dpi=110)


if __name__ == "__main__":
    main()
