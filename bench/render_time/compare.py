#!/usr/bin/env python3
"""Single-threaded render time of two kasha binaries side by side (issue 32's "no slower").

For every (scene, integrator) both binaries render the same image `--runs` times, interleaved
(reference, candidate, reference, ...) so that a change in the machine's load reaches both alike;
the table gives the median of the `seconds` each run's statistics JSON records, and their ratio.

    python3 bench/render_time/compare.py --reference REF/kasha --candidate build/kasha \
        --scenes scenes/jung18_fig1.json scenes/jung18_fig4.json ../shared/peers/cornell_plain_256.json \
        --integrators pt,lt,bdpt,ppm,vcm --spp 16 --runs 3
"""
import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile


def render_seconds(binary, scene, integrator, spp, out_dir, extra):
    exr = os.path.join(out_dir, "render.exr")
    cmd = [binary, "render", scene, "--integrator", integrator, "--spp", str(spp), "--threads", "1",
           "--no-png", "-q", "-o", exr] + extra
    done = subprocess.run(cmd, capture_output=True, text=True)
    if done.returncode != 0:
        return None, done.stderr.strip().splitlines()[-1] if done.stderr.strip() else "exit %d" % done.returncode
    with open(os.path.join(out_dir, "render.stats.json")) as f:
        return json.load(f)["seconds"], None


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--reference", required=True)
    ap.add_argument("--candidate", required=True)
    ap.add_argument("--scenes", nargs="+", required=True)
    ap.add_argument("--integrators", default="pt,lt,bdpt,ppm,vcm")
    ap.add_argument("--spp", type=int, default=16)
    ap.add_argument("--runs", type=int, default=3)
    ap.add_argument("--extra", nargs=argparse.REMAINDER, default=[], help="further kasha render options (last)")
    a = ap.parse_args()
    print("| scene | integrator | reference s | candidate s | candidate / reference |")
    print("|---|---|---|---|---|")
    worst = 0.0
    with tempfile.TemporaryDirectory() as tmp:
        for scene in a.scenes:
            for integrator in a.integrators.split(","):
                times = {"reference": [], "candidate": []}
                error = None
                for _ in range(a.runs):
                    for side in ("reference", "candidate"):
                        s, error = render_seconds(getattr(a, side), scene, integrator, a.spp, tmp, a.extra)
                        if s is None:
                            break
                        times[side].append(s)
                    if error:
                        break
                name = os.path.basename(scene)
                if error:
                    print("| %s | %s | refused: %s | | |" % (name, integrator, error))
                    continue
                ref, cand = statistics.median(times["reference"]), statistics.median(times["candidate"])
                worst = max(worst, cand / ref)
                print("| %s | %s | %.3f | %.3f | %.3f |" % (name, integrator, ref, cand, cand / ref), flush=True)
    print("\nworst ratio %.3f" % worst)
    return 0


if __name__ == "__main__":
    sys.exit(main())
