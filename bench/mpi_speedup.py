#!/usr/bin/python3
"""Speed-up of MPI-distributed rendering (README "Distributed rendering"): renders a scene with one
process and with `mpirun -np 2`, several times each, and prints the median wall-clock time of each
setting and the speed-up of 2 ranks over 1. Two comparisons:

  - the whole machine both ways: 1 process with every core's threads against 2 ranks (Open MPI
    binds each rank to a core when ranks do not outnumber cores, so each runs one thread);
  - one thread per process: 1 process against 2 ranks of one thread each (the ideal is 2×; the
    difference is what the distribution costs: launching, sending the passes, rank 0's commits).

    python3 bench/mpi_speedup.py [--kasha build/kasha] [--scene scenes/cornell_fluorescent.json]
                                 [--spp 16] [--repeats 3] [--integrator pt]

Wall-clock time includes starting the processes (mpirun's launch for the ranks); the render time
reported by kasha's statistics is printed beside it. Every MPI image is checked to be the same bytes
as the one-process image.
"""
import argparse
import filecmp
import json
import os
import statistics
import subprocess
import sys
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def mpirun(ranks):
    # Shared memory between the ranks, the launcher on loopback (a container without a network);
    # as root Open MPI needs --allow-run-as-root.
    cmd = ["mpirun", "--oversubscribe", "-np", str(ranks), "--mca", "btl", "self,vader",
           "--mca", "oob_tcp_if_include", "lo"]
    if os.geteuid() == 0:
        cmd.append("--allow-run-as-root")
    return cmd


def run(cmd, out):
    start = time.monotonic()
    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL)
    wall = time.monotonic() - start
    with open(os.path.splitext(out)[0] + ".stats.json") as f:
        return wall, json.load(f)["seconds"]


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--kasha", default=os.path.join(ROOT, "build", "kasha"))
    p.add_argument("--scene", default=os.path.join(ROOT, "scenes", "cornell_fluorescent.json"))
    p.add_argument("--spp", type=int, default=16)
    p.add_argument("--repeats", type=int, default=3)
    p.add_argument("--integrator", default="pt")
    a = p.parse_args()
    settings = [  # label, launcher prefix, --threads (0: every core)
        ("1 process, all cores", [], 0),
        ("2 ranks, all cores", mpirun(2), 0),
        ("1 process, 1 thread", [], 1),
        ("2 ranks, 1 thread each", mpirun(2), 1),
    ]
    with tempfile.TemporaryDirectory() as tmp:
        times, reference = {}, os.path.join(tmp, "reference.exr")
        for rep in range(a.repeats):
            for label, launcher, threads in settings:  # interleaved, so load changes hit every setting
                out = os.path.join(tmp, f"r{rep}_{len(times.get(label, []))}_{threads}_{len(launcher)}.exr")
                cmd = launcher + [a.kasha, "render", a.scene, "--spp", str(a.spp), "--integrator", a.integrator,
                                  "--threads", str(threads), "-o", out, "--no-png", "-q"]
                times.setdefault(label, []).append(run(cmd, out))
                if not os.path.exists(reference):
                    os.replace(out, reference)
                elif not filecmp.cmp(reference, out, shallow=False):
                    sys.exit(f"mpi_speedup: error: {out} ({label}) differs from the one-process image")
        load = os.getloadavg()
        print(f"{os.path.basename(a.scene)}, {a.integrator}, {a.spp} spp, median of {a.repeats}; "
              f"{os.cpu_count()} cores, load average {load[0]:.1f} {load[1]:.1f} {load[2]:.1f}")
        med = {label: (statistics.median(w for w, _ in t), statistics.median(s for _, s in t)) for label, t in times.items()}
        for label, (wall, render) in med.items():
            print(f"  {label:24s} {wall:7.2f} s wall, {render:7.2f} s rendering")
        for one, two in (("1 process, all cores", "2 ranks, all cores"), ("1 process, 1 thread", "2 ranks, 1 thread each")):
            print(f"speed-up of 2 ranks over 1 ({one.split(', ')[1]}): {med[one][0] / med[two][0]:.2f}x wall-clock, "
                  f"{med[one][1] / med[two][1]:.2f}x rendering")


if __name__ == "__main__":
    main()
