#!/usr/bin/env python3
"""The plain Cornell box of ../shared/peers with a homogeneous medium sphere, for kasha (JSON) and
pbrt-v4 (.pbrt): issue 33's side-by-side scene for media.

Both files start from the plain box that ../shared/peers/make_scenes.py wrote (its kasha JSON and
its pbrt-v4 world, read as they are, so that the box stays the one of the peers' README: same
triangles, spectra, camera, light scale, depth 9) and add the same sphere: index-matched (no
surface), absorbing and scattering, Henyey-Greenstein g = 0.5, above the short block. The pbrt
file is self-contained (its world inline) and uses pbrt-v4's "volpath" (its "path" ignores media).

Usage: make_cornell_medium.py [--peers DIR] [--out DIR]   (default: ../../../shared/peers, this folder)
"""
import argparse
import copy
import json
import os

HERE = os.path.dirname(os.path.abspath(__file__))

# The sphere (millimetres, as the box): centre above the short block (top at y = 165), radius 90.
CENTER, RADIUS, G = (186.0, 275.0, 169.0), 90.0, 0.5
# Coefficients per millimetre, piecewise linear in nm over the whole 360-830 nm range (pbrt's
# piecewise-linear spectra are zero outside their table, kasha's continue the end values: with
# both ends given the two agree). A yellowish haze: absorbs blue more than red; mean free path 8 cm.
SIGMA_S = [(360, 0.0125), (830, 0.0125)]
SIGMA_A = [(360, 0.006), (450, 0.006), (600, 0.001), (830, 0.001)]


def kasha_spectrum(points):
    return {'type': 'tabulated', 'wavelengths': [p[0] for p in points], 'values': [p[1] for p in points]}


def pbrt_spectrum(points):
    return '[ ' + ' '.join(f'{l:g} {v:g}' for l, v in points) + ' ]'


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument('--peers', default=os.path.join(HERE, '..', '..', '..', 'shared', 'peers'))
    ap.add_argument('--out', default=HERE)
    ap.add_argument('--res', type=int, default=256)
    a = ap.parse_args()

    with open(os.path.join(a.peers, f'cornell_plain_{a.res}.json')) as f:
        box = json.load(f)
    scene = copy.deepcopy(box)
    scene['description'] = ('Plain Cornell box of shared/peers with an index-matched sphere of a homogeneous, '
                            'absorbing and scattering medium (g = 0.5): the kasha side of the pbrt-v4 comparison '
                            'of media (bench/peers/make_cornell_medium.py; twin: cornell_medium_256.pbrt).')
    scene['media'] = {'haze': {'type': 'homogeneous', 'sigma_a': kasha_spectrum(SIGMA_A),
                               'sigma_s': kasha_spectrum(SIGMA_S), 'g': G}}
    scene['shapes'].append({'name': 'haze_sphere', 'type': 'sphere', 'center': list(CENTER), 'radius': RADIUS,
                            'interior': 'haze'})
    kpath = os.path.join(a.out, f'cornell_medium_{a.res}.json')
    with open(kpath, 'w') as f:
        json.dump(scene, f, indent=1)

    with open(os.path.join(a.peers, 'cornell_plain_world.pbrt')) as f:
        world = [l.rstrip('\n') for l in f if not l.startswith('#')]
    with open(os.path.join(a.peers, f'cornell_plain_{a.res}_path.pbrt')) as f:
        header = [l.rstrip('\n') for l in f if not l.startswith('#') and not l.startswith('Include')]
    lines = ['# Cornell box of shared/peers with a homogeneous medium sphere, pbrt-v4 "volpath"',
             '# (bench/peers/make_cornell_medium.py; twin of cornell_medium_256.json).',
             '# Scale -1 1 1 mirrors the camera so that the image matches kasha (see shared/peers/README.md).']
    for l in header:
        if l.startswith('Integrator'):
            l = l.replace('"path"', '"volpath"')
        if '"string filename"' in l:
            l = l.replace('cornell_plain.exr', 'cornell_medium.exr')
        lines.append(l)
    lines += world
    lines += ['AttributeBegin',
              '  # haze_sphere: index-matched boundary ("interface"), the medium inside, vacuum outside',
              '  MakeNamedMedium "haze" "string type" "homogeneous"',
              f'      "spectrum sigma_a" {pbrt_spectrum(SIGMA_A)}',
              f'      "spectrum sigma_s" {pbrt_spectrum(SIGMA_S)}',
              f'      "float g" [ {G:g} ] "float scale" [ 1 ]',
              '  MediumInterface "haze" ""',
              '  Material "interface"',
              '  Translate {:g} {:g} {:g}'.format(*CENTER),
              f'  Shape "sphere" "float radius" [ {RADIUS:g} ]',
              'AttributeEnd']
    ppath = os.path.join(a.out, f'cornell_medium_{a.res}.pbrt')
    with open(ppath, 'w') as f:
        f.write('\n'.join(lines) + '\n')
    print(kpath)
    print(ppath)


if __name__ == '__main__':
    main()
