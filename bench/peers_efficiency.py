#!/usr/bin/python3
"""kasha's side of the pbrt-v4 comparison in ../shared/peers (issue 12's table): renders the plain
Cornell box (256x256, max depth 9, 2 threads) with each kasha configuration for 64 spp and three
seeds, times each render (whole process, median of the three; with --repeat N the least of N
rounds of each), measures the reference-free
variance between the seeds with ../shared/peers/compare.py (linear sRGB, mean over pixels and
channels, with and without the pixels that see the light), and prints the efficiency against
pbrt-v4's figures in ../shared/peers/RESULTS.md: (var_pbrt x t_pbrt) / (var_kasha x t_kasha),
> 1 when kasha wins. pbrt's times were measured on a 2-core machine of the same kind; compare
wall times only on an idle machine (or pair the runs with ../shared/peers/bench.sh time).

  /usr/bin/python3 bench/peers_efficiency.py [--kasha build/kasha] [--out DIR] [--configs pt,bdpt-independent,...]
                                             [--repeat N]

Each configuration is an integrator name with optional extra options after a colon, e.g.
"pt:--hero 1". compare.py reads EXR through tools/exr2npy.cpp of the same folder, compiled here
into --out on first use (g++ and OpenEXR's pkg-config, both kasha build dependencies).
"""
import argparse
import json
import os
import statistics
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
PEERS = os.path.normpath(os.path.join(HERE, '..', '..', 'shared', 'peers'))

# pbrt-v4 (zsobol) in ../shared/peers/RESULTS.md: §2 error at 64 spp (all / no emitter), §3 wall s.
PBRT = {
    'path': (1.29e-4, 6.92e-5, 13.07),
    'bdpt': (8.44e-5, 2.57e-5, 63.2),
    'sppm': (6.08e-5, 1.03e-5, 45.7),  # pbrt's sppm error is its MSE minus its reference's variance (bias included)
}
PEER_OF = {'pt': 'path', 'lt': 'path', 'bdpt': 'bdpt', 'bdpt-shared': 'bdpt', 'bdpt-independent': 'bdpt', 'ppm': 'sppm'}


def exr2npy(out):
    tool = os.path.join(out, 'exr2npy')
    if not os.path.exists(tool):
        flags = subprocess.run(['pkg-config', '--cflags', '--libs', 'OpenEXR'], check=True, capture_output=True,
                               text=True).stdout.split()
        subprocess.run(['g++', '-O2', '-std=c++17', os.path.join(PEERS, 'tools', 'exr2npy.cpp'), '-o', tool] + flags,
                       check=True)
    return tool


def render(kasha, integrator, extra, seed, path):
    cmd = [kasha, 'render', os.path.join(PEERS, 'cornell_plain_256.json'), '--integrator', integrator, '--spp', '64',
           '--seed', str(seed), '--threads', '2', '-q', '--no-png', '-o', path] + extra
    start = time.monotonic()
    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL)
    return time.monotonic() - start


def main():
    ap = argparse.ArgumentParser(description=__doc__.split('\n\n')[0])
    ap.add_argument('--kasha', default=os.path.join(HERE, '..', 'build', 'kasha'))
    ap.add_argument('--out', default='/tmp/kasha-peers')
    ap.add_argument('--configs', default='pt,pt:--hero 1,bdpt-independent,bdpt-shared')
    ap.add_argument('--repeat', type=int, default=1,
                    help='rounds of every render, the configurations taken in turn in each round; a '
                         "render's time is its least over the rounds (the wall times of a shared "
                         'machine scatter by 15%% and more between runs)')
    a = ap.parse_args()
    os.makedirs(a.out, exist_ok=True)
    env = dict(os.environ, EXR2NPY=exr2npy(a.out))
    configs = a.configs.split(',')
    seeds = (1, 2, 3)

    def path_of(config, seed):
        return os.path.join(a.out, config.replace(':', '_').replace(' ', '').replace('-', '') + f'_s{seed}.exr')

    least = {}
    for _round in range(max(1, a.repeat)):
        for config in configs:
            integrator, _, extra = config.partition(':')
            for seed in seeds:
                t = render(a.kasha, integrator, extra.split(), seed, path_of(config, seed))
                least[config, seed] = min(t, least.get((config, seed), t))
    rows = []
    for config in configs:
        integrator = config.partition(':')[0]
        files = [path_of(config, seed) for seed in seeds]
        times = [least[config, seed] for seed in seeds]
        var = json.loads(subprocess.run([sys.executable, os.path.join(PEERS, 'compare.py'), 'var',
                                         'x=' + ','.join(files)], check=True, capture_output=True, text=True,
                                        env=env).stdout)['x']
        rows.append((config, statistics.median(times), var['var_rgb'], var['var_rgb_no_emitter'],
                     PBRT[PEER_OF[integrator]] if integrator in PEER_OF else None))
    print(f'| kasha | wall s | time / {configs[0]} | var all | var no em. | pbrt | efficiency all / no em. |')
    print('|---|---|---|---|---|---|---|')
    for config, t, v, vn, peer in rows:
        eff = f'{peer[0] * peer[2] / (v * t):.2f} / {peer[1] * peer[2] / (vn * t):.2f}' if peer else '-'
        print(f'| {config} | {t:.2f} | {t / rows[0][1]:.2f} | {v:.3g} | {vn:.3g} | '
              f'{PEER_OF.get(config.partition(":")[0], "-")} | {eff} |')


if __name__ == '__main__':
    main()
