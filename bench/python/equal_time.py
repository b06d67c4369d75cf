#!/usr/bin/python3
"""Equal-time comparison from Python, with the module `kasha` (README "Python").

Renders a reference of the UV Cornell box (scenes/cornell_uv.json, at a reduced resolution), then
each integrator for the same wall-clock budgets, measures relMSE against the reference in-process
and plots relMSE against time (log-log), plus the spectrum of the fluorescent sphere's pixels from
the reference's spectral bins:

    PYTHONPATH=build/python python3 bench/python/equal_time.py [-o equal_time.png] [--quick]
"""
import argparse
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import kasha  # noqa: E402

REPO = os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", ".."))


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("-o", "--output", default="equal_time.png", help="the figure (PNG)")
    ap.add_argument("--quick", action="store_true", help="shorter budgets and reference (about 30 s in all)")
    ap.add_argument("--resolution", type=int, default=96, help="image width and height")
    a = ap.parse_args()
    budgets = [0.1, 0.2, 0.4] if a.quick else [0.25, 0.5, 1.0, 2.0]
    reference_time = 8.0 if a.quick else 60.0
    integrators = ["pt", "lt", "bdpt-independent", "ppm"]

    scene = kasha.Scene(os.path.join(REPO, "scenes", "cornell_uv.json"))
    scene.set("/camera/resolution", [a.resolution, a.resolution])
    progress = lambda spp, t, total: print(f"\r  reference: {t:5.1f} s, {spp} spp", end="", file=sys.stderr)  # noqa
    ref = kasha.render(scene, integrator="bdpt-independent", time=reference_time, seed=1000003, spectral_step=10,
                       progress=progress)
    print(file=sys.stderr)

    fig, (ax, ax2) = plt.subplots(1, 2, figsize=(10, 4))
    for name in integrators:
        times, errors = [], []
        for budget in budgets:
            r = kasha.render(scene, integrator=name, time=budget, seed=1)
            times.append(r["stats"]["seconds"])
            errors.append(kasha.metrics(r["xyz"], ref["xyz"])["relmse"])
            print(f"{name:<18} {budget:5.2f} s budget: {r['stats']['seconds']:.2f} s, {r['stats']['spp']:5d} spp, "
                  f"relMSE {errors[-1]:.4g}")
        ax.loglog(times, errors, "o-", label=name)
    ax.set_xlabel("render time (s)")
    ax.set_ylabel("relMSE against the reference")
    ax.set_title("cornell_uv: equal time")
    ax.legend()

    # The spectrum of the brightest tenth of the pixels (the fluorescent sphere under UV).
    luminance = ref["xyz"][:, :, 1]
    bright = luminance >= np.quantile(luminance, 0.9)
    ax2.plot(ref["wavelengths"], ref["spectral"][bright].mean(axis=0), drawstyle="steps-mid")
    ax2.set_xlabel("wavelength (nm)")
    ax2.set_ylabel("radiance per nm (bin means)")
    ax2.set_title("brightest 10% of the reference's pixels")
    fig.tight_layout()
    fig.savefig(a.output, dpi=100)
    print(f"wrote {a.output}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
