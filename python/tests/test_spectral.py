"""Spectral bins from Python and the spectral OpenEXR (Fichet et al. 2021 emissive layout)."""
import numpy as np
import pytest

import kasha
from conftest import furnace_dict, furnace_radiance, pixel_mean_and_sigma, seed_mean_and_sigma


def bin_average(lo, hi, c):
    lam = np.linspace(lo, hi, 20001)
    return np.trapz(furnace_radiance(lam, c), lam) / (hi - lo)


@pytest.mark.parametrize("integrator", ["pt", "lt", "bdpt", "ppm"])
def test_furnace_bins_match_the_closed_form_spectrum(integrator):
    # Light tracing draws no camera wavelength: it keeps the default sensor setting.
    sensor = {"sensor_sampling": "cmf"} if integrator == "lt" else {}
    if integrator == "ppm":
        scene = kasha.Scene.from_dict(furnace_dict(c=1.0, resolution=8, spp=64))
        render = lambda seed: kasha.render(scene, integrator="ppm", spectral_step=10, seed=seed)["spectral"]  # noqa
        mean, sigma = seed_mean_and_sigma(render, range(1, 17))
        result = kasha.render(scene, integrator="ppm", spectral_step=10, spp=1)
    else:
        scene = kasha.Scene.from_dict(furnace_dict(c=1.0, resolution=16, spp=64))
        result = kasha.render(scene, integrator=integrator, spectral_step=10, **sensor)
        mean, sigma = pixel_mean_and_sigma(result["spectral"])
    wl, width = result["wavelengths"], result["bin_width"]
    # Every integrator keeps bins with its default four wavelength lanes (lt: one splat per lane;
    # pt and ppm: the lanes keep each sensor wavelength's share apart).
    assert result["stats"]["hero_wavelengths"] == 4
    assert width == pytest.approx(10.0) and len(wl) == 47 and wl[0] == pytest.approx(365.0)
    exact = np.array([bin_average(c - width / 2, c + width / 2, 1.0) for c in wl])
    assert np.all(sigma > 0)
    assert np.all(np.abs(mean - exact) < 4 * sigma), np.c_[wl, mean, exact, sigma]


def test_bins_integrate_to_the_xyz_layer(cmf):
    lam, x, y, z = cmf
    scene = kasha.Scene.from_dict(furnace_dict(c=1.0, resolution=8, spp=16))
    result = kasha.render(scene, spectral_bins=470)  # 1 nm
    bins, xyz, wl, width = result["spectral"], result["xyz"], result["wavelengths"], result["bin_width"]
    y_integral = np.trapz(y, lam)
    fine = np.arange(360.0, 830.0, 0.05) + 0.025
    for k, f in enumerate((x, y, z)):
        f_fine = np.interp(fine, lam, f)
        index = np.minimum(((fine - 360.0) // width).astype(int), len(wl) - 1)
        integral = np.bincount(index, f_fine * 0.05, minlength=len(wl))  # ∫ over each bin
        swing = np.array([np.ptp(f_fine[index == b]) for b in range(len(wl))])  # max − min in each bin
        from_bins = bins @ integral / y_integral
        # Each sample adds W(λ)·v to the XYZ layer and v/Δ to its bin: the two differ only by the
        # observer's variation inside the bin, at most Σ_b bin_b·Δ·swing_b / ∫ȳ (values are ≥ 0).
        bound = bins @ (width * swing) / y_integral
        assert np.all(np.abs(from_bins - xyz[:, :, k]) <= bound + 1e-5 * np.abs(xyz[:, :, k]))
        # Over the image the within-bin differences average out (to second order in Δ).
        assert abs(from_bins.mean() / xyz[:, :, k].mean() - 1.0) < 0.005


def test_spectral_exr_reads_back_bit_exactly(tmp_path):
    scene = kasha.Scene.from_dict(furnace_dict(resolution=6, spp=4))
    out = str(tmp_path / "furnace.exr")
    result = kasha.render(scene, spectral_step=5, output=out)
    back = kasha.read_exr(out)
    np.testing.assert_array_equal(back["spectral"], result["spectral"])
    np.testing.assert_array_equal(back["wavelengths"], result["wavelengths"])
    np.testing.assert_array_equal(back["xyz"], result["xyz"])
