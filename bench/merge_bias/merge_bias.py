#!/usr/bin/env python3
"""Vertex merging's bias falling with passes (issue 14, docs/bdpt-mis.md §12).

Renders scenes/validation/single_plane_point.json (a fluorescent plane under a point light, whose
irradiance varies over any merge disc) with `bpm` and `vcm` at a deliberately large first radius,
for 1, 4, 16, 64, 256 passes (one sample per pixel and the same light subpaths each), with several
seeds, and prints per pass count the mean image luminance Y, its standard error over the seeds, the
error against the closed form and, for `bpm`, the error predicted by blurring the closed form with
each pass's disc (bench/merge_bias/merge_bias_reference, built from tests/point_lit_plane.h).

    PYTHONPATH=build/python python3 bench/merge_bias/merge_bias.py --build-dir build
"""
import argparse
import json
import math
import os
import subprocess
import sys
import time


def parse_args():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--build-dir", default="build")
    p.add_argument("--scene", default="scenes/validation/single_plane_point.json")
    p.add_argument("--radius", type=float, default=1.0, help="first merge radius r_1 (the light's height is 1)")
    p.add_argument("--alpha", type=float, default=2.0 / 3.0)
    p.add_argument("--photons", type=int, default=1024, help="light subpaths per pass")
    p.add_argument("--passes", default="1,4,16,64,256")
    p.add_argument("--seeds", type=int, default=64)
    p.add_argument("--integrators", default="bpm,vcm")
    p.add_argument("--out", help="also write the table (Markdown) to this file")
    return p.parse_args()


def reference(args, passes):
    """The closed form and the blurred images, from the C++ helper."""
    exe = os.path.join(args.build_dir, "bench", "merge_bias_reference")
    cmd = [exe, args.scene, repr(args.radius), repr(args.alpha)] + [str(p) for p in passes]
    return json.loads(subprocess.run(cmd, check=True, capture_output=True, text=True).stdout)


def mean_and_stderr(values):
    n = len(values)
    mean = sum(values) / n
    var = sum((v - mean) ** 2 for v in values) / (n - 1)
    return mean, math.sqrt(var / n)


def main():
    args = parse_args()
    sys.path.insert(0, os.path.join(args.build_dir, "python"))
    import kasha  # noqa: E402 (the module of this build)

    passes = [int(p) for p in args.passes.split(",")]
    ref = reference(args, passes)
    exact_y = ref["exact"][1]
    scene = kasha.Scene(args.scene)
    ppm = {"radius": args.radius, "alpha": args.alpha, "photons_per_pass": args.photons}
    rows = []
    for integrator in args.integrators.split(","):
        for p in passes:
            start = time.perf_counter()
            ys = []
            for seed in range(1, args.seeds + 1):
                r = kasha.render(scene, integrator=integrator, spp=p, seed=seed, threads=1, ppm=ppm)
                assert r["stats"]["spp"] == p
                ys.append(float(r["xyz"][:, :, 1].astype("float64").mean()))
            seconds = time.perf_counter() - start
            mean, se = mean_and_stderr(ys)
            blurred = ref["passes"][str(p)]["blurred"][1]
            rows.append({
                "integrator": integrator, "passes": p, "radius": ref["passes"][str(p)]["radius"],
                "mean": mean, "se": se, "error": mean - exact_y,
                "predicted": blurred - exact_y if integrator == "bpm" else None, "seconds": seconds,
            })
            print(f"{integrator} {p} passes: Y {mean:.5f} ± {se:.5f} (exact {exact_y:.5f}), {seconds:.1f} s",
                  file=sys.stderr)

    lines = [
        f"Y of the mean image, exact {exact_y:.5f}; r_1 = {args.radius}, α = {args.alpha:.3g}, "
        f"{args.photons} light subpaths per pass, {args.seeds} seeds per row (σ: their standard error).",
        "",
        "| integrator | passes | r_P | mean Y | σ | mean − exact | (mean − exact)/σ | blur's error (bpm) | s |",
        "|---|---|---|---|---|---|---|---|---|",
    ]
    for r in rows:
        pred = f"{r['predicted']:+.5f} ({100 * r['predicted'] / exact_y:+.1f}%)" if r["predicted"] is not None else "–"
        lines.append(
            f"| {r['integrator']} | {r['passes']} | {r['radius']:.3f} | {r['mean']:.5f} | {r['se']:.5f} | "
            f"{r['error']:+.5f} ({100 * r['error'] / exact_y:+.1f}%) | {r['error'] / r['se']:+.1f} | {pred} | "
            f"{r['seconds']:.1f} |")
    table = "\n".join(lines)
    print(table)
    if args.out:
        with open(args.out, "w") as f:
            f.write(table + "\n")


if __name__ == "__main__":
    main()
