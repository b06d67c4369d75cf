"""Shared pieces of the Python module's tests: the closed-form furnace of docs/validation.md §1 as a
scene dict, its exact spectrum by quadrature, and the CIE 1931 observer read from the repository's
table (independently of the module)."""
import os

import numpy as np
import pytest

REPO = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))


def furnace_dict(c=1.0, resolution=16, spp=64, seed=7):
    """docs/validation.md §1: a sphere seen from inside, every surface Jung's BBRRDF (a = 0.8 on
    [400, 450), e = 1/50 on [550, 600), r = 0.5, Q = 0.9) emitting L_e = 1."""
    return {
        "render": {"spp": spp, "max_depth": 1000, "rr_depth": 3, "seed": seed, "sensor_sampling": "uniform"},
        "camera": {"position": [0, 0, 0], "look_at": [0, 0, 1], "up": [0, 1, 0], "fov": 60,
                   "resolution": [resolution, resolution]},
        "materials": {"wall": {"type": "jung_fluorescent",
                               "absorption": {"type": "box", "min": 400, "max": 450, "value": 0.8},
                               "emission": {"type": "box", "min": 550, "max": 600, "value": 0.02},
                               "reflectance": 0.5, "c": c, "Q": 0.9}},
        "shapes": [{"name": "enclosure", "type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "wall",
                    "emission": {"radiance": 1.0, "two_sided": True}}],
    }


def furnace_radiance(lam, c):
    """L(λ) = [L_e + Q·e·K] / D, D = 1 − (1 − c·a)·r, K = A / (1 − Q·B) (docs/validation.md §1), by
    quadrature on a 0.01 nm grid over 360–830 nm."""
    grid = np.arange(360.0, 830.0, 0.01) + 0.005
    a = lambda l: np.where((l >= 400) & (l < 450), 0.8, 0.0)
    e = lambda l: np.where((l >= 550) & (l < 600), 0.02, 0.0)
    D = lambda l: 1.0 - (1.0 - c * a(l)) * 0.5
    A = np.sum(c * a(grid) * 1.0 / D(grid)) * 0.01
    B = np.sum(c * a(grid) * e(grid) / D(grid)) * 0.01
    K = A / (1.0 - 0.9 * B)
    return (1.0 + 0.9 * e(lam) * K) / D(lam)


@pytest.fixture(scope="session")
def cmf():
    """(λ, x̄, ȳ, z̄) of the CIE 1931 2° observer, 1 nm, 360–830 nm."""
    path = os.path.join(REPO, "scenes", "spectra", "cie1931_2deg_cmf_1nm.csv")
    rows = [l for l in open(path) if l.strip() and not l.startswith("#")]
    data = np.array([[float(v) for v in l.split(",")] for l in rows[1:]])
    return data[:, 0], data[:, 1], data[:, 2], data[:, 3]


def pixel_mean_and_sigma(values):
    """Mean over pixels (axes 0, 1) and its standard error, for integrators whose pixels are
    independent estimates (each draws from its own random streams; splats from independent light
    subpaths). Not photon mapping: a pass's pixels share one photon map."""
    n = values.shape[0] * values.shape[1]
    flat = values.reshape(n, -1)
    return flat.mean(axis=0), flat.std(axis=0, ddof=1) / np.sqrt(n)


def seed_mean_and_sigma(render, seeds):
    """Mean over independent renders (one per seed) of their image means, and its standard error:
    for photon mapping, whose pixels are correlated through the pass's shared photon map."""
    means = np.array([render(seed).mean(axis=(0, 1)) for seed in seeds])
    return means.mean(axis=0), means.std(axis=0, ddof=1) / np.sqrt(len(seeds))
