#!/usr/bin/env python3
"""Writes the closed meshes and the Lumogen spectrum of the participating-media scenes
(scenes/tonic_water.json, fluorescein_cuvette.json, lsc_slab.json, uv_dye_caustic.json;
docs/media-scenes.md), and prints the energy yields the scenes use.

Every mesh is a closed surface of revolution: a profile (r, y) in a half-plane, from a point on the
axis back to a point on the axis with the solid on its left (counter-clockwise), turned about the
y axis in `segments` steps. Four segments turned by 45 degrees make a square prism (cuvette, slab).
Triangles face outwards (away from the solid), as kasha's dielectric needs: the inside of a
dielectric is the side its normals point away from (docs/scene-format.md).

Units: centimetres (the scenes' length_unit). Run from anywhere: python3 scenes/media/make_media_meshes.py
"""
import math
import os

HERE = os.path.dirname(os.path.abspath(__file__))
SPECTRA = os.path.join(HERE, '..', 'spectra')

# Gap between a container's inner wall and its liquid (cm): a shape separating two media must be
# closed on its own, so the liquid is its own closed water surface 0.1 mm inside the glass.
GAP = 0.01


def revolve(profile, segments, phase_deg=0.0):
    """Vertices and outward-facing triangles of the profile turned about the y axis."""
    verts, index = [], {}

    def vertex(i, j):
        r, y = profile[i]
        key = (i, 0) if r == 0.0 else (i, j % segments)
        if key not in index:
            a = math.radians(phase_deg) + 2.0 * math.pi * (j % segments) / segments
            index[key] = len(verts)
            verts.append((r * math.cos(a), y, r * math.sin(a)))
        return index[key]

    tris = []
    for i in range(len(profile) - 1):
        (ra, ya), (rb, yb) = profile[i], profile[i + 1]
        # Outward normal of the counter-clockwise profile edge a->b in the (r, y) plane: (dy, -dr).
        out_r, out_y = yb - ya, -(rb - ra)
        for j in range(segments):
            quad = [vertex(i, j), vertex(i + 1, j), vertex(i + 1, j + 1), vertex(i, j + 1)]
            for t in ([quad[0], quad[1], quad[2]], [quad[0], quad[2], quad[3]]):
                if len(set(t)) < 3:
                    continue  # the pole's side of a fan
                p = [verts[k] for k in t]
                u = [p[1][c] - p[0][c] for c in range(3)]
                v = [p[2][c] - p[0][c] for c in range(3)]
                n = (u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0])
                cx, cz = sum(q[0] for q in p) / 3, sum(q[2] for q in p) / 3
                rad = math.hypot(cx, cz) or 1.0
                expected = (out_r * cx / rad, out_y, out_r * cz / rad)
                if sum(n[c] * expected[c] for c in range(3)) < 0.0:
                    t = [t[0], t[2], t[1]]
                tris.append(t)
    return verts, tris


def write_obj(name, what, verts, tris):
    path = os.path.join(HERE, name)
    with open(path, 'w') as f:
        f.write(f'# {what}\n# Written by make_media_meshes.py (closed, outward normals, centimetres).\n')
        for v in verts:
            f.write('v {:.6f} {:.6f} {:.6f}\n'.format(*v))
        for t in tris:
            f.write('f {} {} {}\n'.format(*(k + 1 for k in t)))
    print(f'{path}: {len(verts)} vertices, {len(tris)} triangles')


def cup(outer, wall, bottom, height):
    """A cup's solid: outer radius, wall thickness, bottom thickness, height (from y = 0)."""
    inner = outer - wall
    return [(0.0, 0.0), (outer, 0.0), (outer, height), (inner, height), (inner, bottom), (0.0, bottom)]


def block(radius, y0, y1):
    """A solid of revolution between heights y0 and y1 (a prism with 4 segments)."""
    return [(0.0, y0), (radius, y0), (radius, y1), (0.0, y1)]


def biconvex_lens(aperture, radius, edge, steps):
    """A symmetric biconvex lens about the y axis: two spherical caps of curvature radius `radius`
    over a rim of radius `aperture` and thickness `edge`, the optical centre at y = 0."""
    sag = lambda r: radius - math.sqrt(radius * radius - r * r)  # noqa: E731  (cap height at r)
    half = edge / 2.0 + sag(aperture)  # half the centre thickness
    rs = [aperture * i / steps for i in range(steps + 1)]
    lower = [(r, -half + sag(r)) for r in rs]
    upper = [(r, half - sag(r)) for r in reversed(rs)]
    return lower + upper


SQUARE = math.sqrt(2.0)  # a square of half-side s has its corners at radius s·√2


def lumogen_csv():
    """pvtrace's fits of Lumogen F Red 305 (danieljfarrell/pvtrace, pvtrace/data/lumogen_f_red_305.py,
    BSD-3-Clause): absorption a sum of five Gaussians exp(-((c - x)/w)^2), emission one, both
    peak-normalised. Tabulated at 1 nm."""
    absorption = [(0.9454846839252642, 578.6167306868869, 22.6976093987002),
                  (0.6430326869158796, 535.1850303736512, 28.63029894331116),
                  (0.1243340609168971, 494.5721783546976, 13.98438275367119),
                  (0.3651471532322375, 440.4679754085741, 34.91923613222621),
                  (0.7042787252835550, 336.0548556730901, 34.24136755250487)]
    lam = list(range(300, 831))
    a = [sum(h * math.exp(-((c - x) / w) ** 2) for h, c, w in absorption) for x in lam]
    peak = max(a)
    e = [math.exp(-((600.0 - x) / 38.60) ** 2) for x in lam]
    path = os.path.join(SPECTRA, 'lumogen_f_red_305_pvtrace_1nm.csv')
    with open(path, 'w') as f:
        f.write('# Lumogen F Red 305 (BASF perylene dye, the usual LSC dye): absorption (abs) and emission (em), '
                'peak-normalised, 300-830 nm, 1 nm.\n')
        f.write('# Source: danieljfarrell/pvtrace @ 1297b376f576467bf97855a00eab2b3f339d437d, '
                'pvtrace/data/lumogen_f_red_305.py: the author\'s fits (absorption: five Gaussians, '
                'emission: one Gaussian at 600 nm) to measured spectra; "good enough for getting sensible answers".\n')
        f.write('# Processing: the two fitted functions evaluated at every nm by scenes/media/make_media_meshes.py '
                '(absorption divided by its maximum over 300-830 nm).\n')
        f.write('# License: BSD-3-Clause (Copyright (c) 2020, Daniel Farrell; pvtrace LICENSE.txt).\n')
        f.write('wavelength_nm,abs,em\n')
        for x, av, ev in zip(lam, a, e):
            f.write(f'{x},{av / peak:.6f},{ev:.6f}\n')
    print(f'{path}: absorption peak at {lam[a.index(peak)]} nm')
    return lam, e, lam[a.index(peak)]


def mean_wavelength(lam, e, lo, hi):
    """Energy-weighted mean wavelength of an emission spectrum over [lo, hi]."""
    pts = [(l, v) for l, v in zip(lam, e) if lo <= l <= hi]
    return sum(l * v for l, v in pts) / sum(v for _, v in pts)


def fitc_emission():
    lam, em = [], []
    with open(os.path.join(SPECTRA, 'dyes_fpbase_fitc_pacificblue_1nm.csv')) as f:
        rows = [r.strip().split(',') for r in f if r.strip() and not r.startswith('#')]
    col = rows[0].index('FITC_em')
    for r in rows[1:]:
        lam.append(float(r[0]))
        em.append(float(r[col]))
    return lam, em


def energy_yield(photon_yield, excitation_nm, mean_emission_nm):
    """kasha's yield is emitted over absorbed ENERGY (core/medium.h). A photon absorbed at λ_x
    carries hc/λ_x, an emitted one on average hc·<1/λ>_photons = hc/<λ>_energy (the photon
    spectrum is the energy spectrum times λ), so Y = Φ·λ_x/<λ_m>_energy."""
    return photon_yield * excitation_nm / mean_emission_nm


def main():
    # Tonic water: a tumbler of 3.2 cm outer radius, 2.5 mm wall, 6 mm base, 10 cm tall, and the
    # liquid filled to 8 cm, 0.1 mm inside it.
    write_obj('tumbler_glass.obj', 'Glass tumbler (tonic_water.json)', *revolve(cup(3.2, 0.25, 0.6, 10.0), 128))
    write_obj('tumbler_liquid.obj', 'Tonic water in the tumbler (tonic_water.json)',
              *revolve(block(3.2 - 0.25 - GAP, 0.6 + GAP, 8.0), 128))
    # Fluorescein: a standard 10 mm cuvette (12.5 mm square outside, 1.25 mm walls, 45 mm tall,
    # 3 mm base), filled to 35 mm.
    write_obj('cuvette_glass.obj', 'Quartz cuvette, 10 mm path (fluorescein_cuvette.json)',
              *revolve(cup(0.625 * SQUARE, 0.125 * SQUARE, 0.3, 4.5), 4, 45.0))
    write_obj('cuvette_liquid.obj', 'Fluorescein solution in the cuvette (fluorescein_cuvette.json)',
              *revolve(block((0.5 - GAP) * SQUARE, 0.3 + GAP, 3.5), 4, 45.0))
    # LSC: a 10 x 10 cm PMMA sheet, 6 mm thick, on a black 6 x 6 cm stand 1.5 cm tall (GAP below
    # the sheet: coplanar faces would leave it to rounding which surface a ray meets first).
    write_obj('lsc_slab.obj', 'Fluorescent PMMA sheet, 10 x 10 x 0.6 cm (lsc_slab.json)',
              *revolve(block(5.0 * SQUARE, 1.5, 2.1), 4, 45.0))
    write_obj('lsc_stand.obj', 'Stand under the sheet (lsc_slab.json)',
              *revolve(block(3.0 * SQUARE, 0.0, 1.5 - GAP), 4, 45.0))

    # UV caustic in a dye (uv_dye_caustic.json): the solution, filling a black cell of 30 mm inner
    # side to 28 mm above its 3 mm base, as an index-matched block (the camera looks into it from
    # above without meeting glass: light tracing, the scene's reference, cannot see through a
    # dielectric); the cell's entrance window, a fused-silica disc 14 mm across and 1.5 mm thick;
    # and a BK7 biconvex lens (16 mm across, curvature radius 22 mm, 1 mm rim: paraxial f = 2.1 cm
    # at 365 nm). The window's and the lens's axes are y here; the scene turns them onto x.
    write_obj('dye_cell_liquid.obj', 'Quinine solution in the black cell, index-matched (uv_dye_caustic.json)',
              *revolve(block((1.5 - GAP) * SQUARE, 0.3 + GAP, 2.8), 4, 45.0))
    write_obj('dye_cell_window.obj', 'Fused-silica entrance window, 14 x 1.5 mm (uv_dye_caustic.json)',
              *revolve(block(0.7, -0.075, 0.075), 64))
    write_obj('dye_cell_lens.obj', 'BK7 biconvex lens, 16 mm, R = 22 mm (uv_dye_caustic.json)',
              *revolve(biconvex_lens(0.8, 2.2, 0.1, 16), 64))

    lam, lumogen_em, lumogen_peak = lumogen_csv()
    fl, fe = fitc_emission()
    print('energy yields Y = phi * lambda_x / <lambda_m>:')
    print(f'  quinine, phi 0.546 (Melhuish 1961), 365 nm LED, Gaussian emission at 450 nm '
          f'(tonic_water.json, uv_dye_caustic.json): {energy_yield(0.546, 365.0, 450.0):.3f}')
    print(f'  fluorescein, phi 0.925 (Magde et al. 2002), 470 nm LED, FITC emission '
          f'<lambda> = {mean_wavelength(fl, fe, 360, 830):.1f} nm: '
          f'{energy_yield(0.925, 470.0, mean_wavelength(fl, fe, 360, 830)):.3f}')
    print(f'  Lumogen F Red 305, phi 0.95, absorption peak {lumogen_peak} nm, emission <lambda> = '
          f'{mean_wavelength(lam, lumogen_em, 360, 830):.1f} nm: '
          f'{energy_yield(0.95, lumogen_peak, mean_wavelength(lam, lumogen_em, 360, 830)):.3f}')


if __name__ == '__main__':
    main()
