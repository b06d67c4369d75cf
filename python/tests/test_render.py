"""kasha.render against closed forms, changing parameters, errors (docs/validation.md §1)."""
import numpy as np
import pytest

import kasha
from conftest import furnace_dict, furnace_radiance, pixel_mean_and_sigma


def expected_xyz(c, cmf):
    lam, x, y, z = cmf
    L = furnace_radiance(lam, c)
    # The film's normalisation (core/color.h): XYZ = ∫ cmf·L dλ / ∫ ȳ dλ (trapezoids on the 1 nm table).
    return np.array([np.trapz(f * L, lam) for f in (x, y, z)]) / np.trapz(y, lam)


@pytest.mark.parametrize("integrator", ["pt", "bdpt"])
def test_furnace_from_dict_then_change_c(integrator, cmf):
    scene = kasha.Scene.from_dict(furnace_dict(c=1.0))
    for c in (1.0, 0.3, 0.0):
        scene.set_material("wall", c=c)
        result = kasha.render(scene, integrator=integrator)
        mean, sigma = pixel_mean_and_sigma(result["xyz"])
        exact = expected_xyz(c, cmf)
        assert np.all(sigma > 0)
        assert np.all(np.abs(mean - exact) < 4 * sigma), (c, mean, exact, sigma)
    # The closed forms differ by far more than the tolerance, so the test sees c change.
    assert abs(expected_xyz(1.0, cmf)[1] - expected_xyz(0.0, cmf)[1]) > 10 * sigma[1]


def test_settings_and_spectra_roundtrip():
    scene = kasha.Scene.from_dict(furnace_dict())
    assert scene.materials == ["wall"]
    assert scene.get("/materials/wall/Q") == 0.9
    lam, val = scene.spectrum("/materials/wall/absorption")
    assert val.max() == pytest.approx(0.8) and lam.min() <= 400 and lam.max() >= 450
    scene.set_spectrum("/materials/wall/absorption", np.array([360.0, 830.0]), np.array([0.1, 0.1]))
    lam, val = scene.spectrum("/materials/wall/absorption")
    np.testing.assert_array_equal(val, np.float32([0.1, 0.1]))
    result = kasha.render(scene, spp=2, max_depth=3, sensor_sampling="cmf", seed=3)
    assert result["stats"]["spp"] == 2 and result["stats"]["max_depth"] == 3
    assert result["stats"]["sensor_sampling"] == "cmf" and result["stats"]["seed"] == 3
    assert result["xyz"].shape == (16, 16, 3) and result["rgb"].shape == (16, 16, 3)


def test_errors_carry_kashas_message(tmp_path):
    scene = kasha.Scene.from_dict(furnace_dict())
    scene.set_material("wall", c=2.0)
    with pytest.raises(kasha.InputError, match=r"/materials/wall/c: .*outside \[0, 1\]"):
        kasha.render(scene, spp=1)
    with pytest.raises(kasha.InputError, match="no_such.json: cannot open scene file"):
        kasha.Scene(str(tmp_path / "no_such.json"))
    bad = tmp_path / "bad.json"
    bad.write_text("{ not json")
    with pytest.raises(kasha.InputError, match="bad.json: malformed JSON"):
        kasha.Scene(str(bad))
    scene.set_material("wall", c=1.0)
    with pytest.raises(kasha.InputError, match="integrator: unknown integrator 'nope'"):
        kasha.render(scene, integrator="nope", spp=1)
    with pytest.raises(kasha.InputError, match="spp: must be positive"):  # more in test_arguments.py
        kasha.render(scene, spp=-3)
    with pytest.raises(kasha.InputError, match="spectral_bins"):
        kasha.render(scene, spp=1, spectral_bins=-2)
    with pytest.raises(kasha.InputError, match=r"/materials/nope: no such material"):
        scene.set_material("nope", c=0.5)
    with pytest.raises(KeyError, match="/materials/wall/nothing"):
        scene.get("/materials/wall/nothing")
    with pytest.raises(kasha.MemoryLimitError, match="memory limit"):
        kasha.render(scene, spp=1, spectral_bins=400, memory_limit="64K")


def test_metrics_on_arrays():
    rng = np.random.default_rng(1)
    ref = rng.uniform(0.0, 2.0, size=(5, 7, 3)).astype(np.float32)
    img = (ref + rng.normal(0.0, 0.1, size=ref.shape)).astype(np.float32)
    m = kasha.metrics(img, ref)
    d = img.astype(np.float64) - ref
    assert m["rmse"] == pytest.approx(np.sqrt(np.mean(d * d)), rel=1e-6)
    assert m["relmse"] == pytest.approx(np.mean(d * d / (ref.astype(np.float64) ** 2 + 1e-2)), rel=1e-6)
    emap = kasha.error_map(img, ref)
    assert emap.shape == (5, 7) and emap.mean() == pytest.approx(m["relmse"], rel=1e-5)
    assert kasha.metrics(ref, ref)["rmse"] == 0.0
    with pytest.raises(kasha.InputError, match="reference"):
        kasha.metrics(img, ref[:, :, :2])


def test_bdpt_strategy_images_sum_to_the_render():
    scene = kasha.Scene.from_dict(furnace_dict(resolution=8, spp=8))
    result = kasha.render(scene, integrator="bdpt", strategy_images=True, max_depth=3)
    weighted = [v for k, v in result["strategies"].items() if not k.endswith("_unweighted")]
    assert len(weighted) > 3
    total = np.sum(weighted, axis=0)
    np.testing.assert_allclose(total, result["xyz"], rtol=1e-4, atol=1e-5)
    with pytest.raises(kasha.InputError, match="has no \\(s, t\\) strategies"):
        kasha.render(scene, integrator="pt", strategy_images=True)


def test_vcm_strategy_images_as_on_the_command_line():
    # Capabilities, not types, decide (integrators/render_job.h): vcm's strategies too, with
    # vcm.paths "auto" run bidirectional as `kasha render --strategy-images` does (docs/cli.md).
    scene = kasha.Scene.from_dict(furnace_dict(resolution=8, spp=2))
    result = kasha.render(scene, integrator="vcm", strategy_images=True, max_depth=3)
    assert "choices" not in result["stats"]  # no pilot: bidirectional
    weighted = [v for k, v in result["strategies"].items() if not k.endswith("_unweighted")]
    np.testing.assert_allclose(np.sum(weighted, axis=0), result["xyz"], rtol=1e-4, atol=1e-5)


def test_settings_other_integrators_read_are_refused():
    # The same rule as `kasha render --set` (integrators/integrator_factory.h, settingNotRead).
    scene = kasha.Scene.from_dict(furnace_dict(resolution=8, spp=1))
    with pytest.raises(kasha.InputError, match="vcm.paths: only for --integrator vcm"):
        kasha.render(scene, integrator="bdpt", vcm={"paths": "camera"})
    with pytest.raises(kasha.InputError, match="bdpt.mollify_alpha: only for --integrator bdpt"):
        kasha.render(scene, integrator="pt", bdpt={"mollify_alpha": 0.5})


def test_bdpt_families_from_python():
    # The fluorescent furnace: `bdpt` runs a pilot and reports its choice; the aliases bdpt-shared
    # and bdpt-independent are bdpt with one family (render/bdpt/families, a dict merged key by key
    # into the scene's own), image for image; a bad choice names the field.
    scene = kasha.Scene.from_dict(furnace_dict(resolution=8, spp=4))
    auto = kasha.render(scene, integrator="bdpt")
    assert auto["stats"]["choices"].startswith("families: ")
    alone = kasha.render(scene, integrator="bdpt", bdpt={"families": "shared"})
    shared = kasha.render(scene, integrator="bdpt-shared")
    np.testing.assert_array_equal(alone["xyz"], shared["xyz"])
    own = kasha.render(scene, integrator="bdpt", bdpt={"families": "own"})
    independent = kasha.render(scene, integrator="bdpt-independent")
    np.testing.assert_array_equal(own["xyz"], independent["xyz"])
    assert "choices" not in kasha.render(scene, integrator="bdpt", bdpt={"families": "both"})["stats"]
    with pytest.raises(kasha.InputError, match="/render/bdpt/families"):
        kasha.render(scene, integrator="bdpt", bdpt={"families": "neither"})


def test_vcm_paths_from_python():
    # vcm runs a pilot and reports its choice; camera paths alone are pt's estimator and the
    # connections alone vc's, image for image; a bad choice names the field.
    scene = kasha.Scene.from_dict(furnace_dict(resolution=8, spp=4))
    auto = kasha.render(scene, integrator="vcm")
    assert auto["stats"]["choices"].startswith("paths: ")
    camera = kasha.render(scene, integrator="vcm", vcm={"paths": "camera"})
    np.testing.assert_array_equal(camera["xyz"], kasha.render(scene, integrator="pt")["xyz"])
    connections = kasha.render(scene, integrator="vcm", vcm={"paths": "connections"})
    np.testing.assert_array_equal(connections["xyz"], kasha.render(scene, integrator="vc")["xyz"])
    for fixed in ("bidirectional", "gather", "connections"):
        assert "choices" not in kasha.render(scene, integrator="vcm", vcm={"paths": fixed})["stats"]
    with pytest.raises(kasha.InputError, match="/render/vcm/paths"):
        kasha.render(scene, integrator="vcm", vcm={"paths": "light"})
