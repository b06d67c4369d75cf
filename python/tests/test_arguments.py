"""Hostile arguments: the module checks them by the command line's rules (core/number_check.h,
integrators/render_numbers.h) and every refusal is a kasha.InputError naming the argument, never a
TypeError from pybind11's conversions, a RuntimeError or a silently odd render."""
import numpy as np
import pytest

import kasha
from conftest import furnace_dict

NAN, INF = float("nan"), float("inf")


def tiny_scene():
    return kasha.Scene.from_dict(furnace_dict(resolution=4, spp=1))


def refused(call, *fragments):
    """`call` raises kasha.InputError whose message holds every fragment."""
    with pytest.raises(kasha.InputError) as e:
        call()
    assert type(e.value) is kasha.InputError
    for f in fragments:
        assert f in str(e.value), (f, str(e.value))


@pytest.mark.parametrize("name, value, reason", [
    ("spp", NAN, "expected a finite integer, got 'nan'"),
    ("spp", INF, "expected a finite integer, got 'inf'"),
    ("spp", -3, "must be positive, got '-3'"),
    ("spp", 0, "must be positive, got '0'"),
    ("spp", 2.5, "expected an integer, got '2.5'"),
    ("spp", 2 ** 31, "must be at most 2147483647"),
    ("spp", 10 ** 400, "expected a finite integer"),
    ("spp", "4", "expected a number, got str '4'"),
    ("spp", True, "expected a number, got bool True"),
    ("spp", [4], "expected a number, got list"),
    ("time", NAN, "expected a finite number, got 'nan'"),
    ("time", -INF, "expected a finite number, got '-inf'"),
    ("time", -1.0, "must not be negative, got '-1.0'"),
    ("seed", -1, "must not be negative"),
    ("seed", 1.5, "expected an integer"),
    ("seed", 2 ** 31, "must be at most 2147483647"),
    ("threads", NAN, "expected a finite integer"),
    ("threads", np.float64(NAN), "expected a finite integer"),
    ("threads", -1, "must not be negative"),
    ("threads", 1.5, "expected an integer"),
    ("threads", 5000, "must be at most 4096"),
    ("threads", None, "expected a number, got NoneType None"),
    ("strategy_depth", NAN, "expected a finite integer"),
    ("strategy_depth", -1, "must not be negative"),
    ("strategy_depth", 65, "must be at most 64"),
    ("strategy_depth", 2.5, "expected an integer"),
    ("spectral_bins", -2, "must not be negative"),
    ("spectral_bins", INF, "expected a finite integer"),
    ("spectral_bins", 4097, "must be at most 4096"),
    ("spectral_step", NAN, "expected a finite number"),
    ("spectral_step", -10.0, "must not be negative"),
    ("spectral_step", 1e-300, "makes more than 4096 bins"),  # not rounded to 0 (no bins) on the way
    ("strategy_images", "yes", "expected True or False, got str 'yes'"),
    ("memory_limit", "lots", "memory_limit"),
    ("memory_limit", 8, "expected a string, got int 8"),
    ("integrator", 3, "expected a string, got int 3"),
    ("integrator", "nope", "unknown integrator 'nope'"),
    ("output", 1, "expected a file name (str or os.PathLike), got int 1"),
    ("progress", 5, "expected a callable or None, got int 5"),
])
def test_render_arguments_are_checked(name, value, reason):
    refused(lambda: kasha.render(tiny_scene(), **{name: value}), "kasha.render: " + name + ": ", reason)


@pytest.mark.parametrize("name, value", [("max_depth", NAN), ("max_depth", INF), ("max_depth", -1),
                                         ("max_depth", 2.5), ("rr_depth", NAN), ("hero_wavelengths", "4"),
                                         ("max_depth", object())])
def test_render_object_keywords_are_checked(name, value):
    # Keys of the render object are checked by the scene loader, as `kasha render --set` is;
    # NaN and objects cannot even be written into it.
    refused(lambda: kasha.render(tiny_scene(), **{name: value}), name)


def test_the_scene_argument_is_checked():
    refused(lambda: kasha.render("scene.json", spp=1), "kasha.render: scene: expected a kasha.Scene, got str")


def test_names_and_dicts_are_checked(tmp_path):
    refused(lambda: kasha.Scene(5), "kasha.Scene: path: expected a file name (str or os.PathLike), got int 5")
    refused(lambda: kasha.Scene.from_dict([1]), "Scene.from_dict: scene: expected a dict, got list [1]")
    refused(lambda: kasha.Scene.from_dict({}, base_dir=None), "Scene.from_dict: base_dir: expected a file name")
    refused(lambda: tiny_scene().get(b"/render"), "Scene.get: pointer: expected a string, got bytes")
    refused(lambda: tiny_scene().spectrum(None), "Scene.spectrum: pointer: expected a string")
    refused(lambda: kasha.read_exr(3.0), "kasha.read_exr: path: expected a file name")
    # os.PathLike names are file names like str ones.
    path = tmp_path / "scene.json"
    path.write_text('{"render": {"spp": 1}}')
    assert kasha.Scene(path).get("/render/spp") == 1


def test_numbers_of_any_python_kind_within_the_rules_are_taken():
    scene = tiny_scene()
    a = kasha.render(scene, spp=np.int64(2), seed=3.0, threads=np.int32(1), time=0, strategy_depth=np.float32(2))
    b = kasha.render(scene, spp=2, seed=3, threads=1)
    assert a["stats"]["spp"] == 2 and a["stats"]["seed"] == 3
    np.testing.assert_array_equal(a["xyz"], b["xyz"])


def test_scene_set_refuses_an_index_past_the_end_of_a_list():
    scene = tiny_scene()
    before = scene.to_dict()
    sphere = before["shapes"][0]
    for pointer in ("/shapes/2", "/shapes/99999999999999999999999", "/render/new/3", "/shapes/0/center/4"):
        refused(lambda: scene.set(pointer, sphere), pointer, "past the end of a list")
    for pointer, value in (("no/slash", 1), ("/render/spp/x", 1), ("/shapes/01", sphere), ("/render/spp", NAN),
                           ("/render/spp", INF), ("/render/spp", {1, 2}), ("/render/spp", object())):
        refused(lambda: scene.set(pointer, value), pointer)
    refused(lambda: scene.set(5, 1), "Scene.set: pointer: expected a string, got int 5")
    refused(lambda: scene.set_material(1, c=0.5), "Scene.set_material: name: expected a string")
    assert scene.to_dict() == before  # nothing was written
    # A list grows by one element at its end; a missing list is made of one element.
    scene.set("/shapes/1", sphere)
    scene.set("/shapes/-", sphere)
    scene.set("/render/new/0", 1)
    assert len(scene.get("/shapes")) == 3 and scene.get("/render/new") == [1]
    scene.set("/shapes/0/center/2", 0.0)
    scene.set_spectrum("/materials/wall/reflectance", np.array([360.0, 830.0]), [0.5, 0.5])
    assert scene.get("/materials/wall/reflectance")["values"] == [0.5, 0.5]
    refused(lambda: scene.set_spectrum("/materials/wall/reflectance", np.array([360.0, NAN]), [0.5, 0.5]),
            "/materials/wall/reflectance", "cannot be written as JSON")


def xyz(h=3, w=4, value=0.5):
    return np.full((h, w, 3), value, dtype=np.float32)


@pytest.mark.parametrize("function", [kasha.metrics, kasha.error_map])
def test_metrics_refuse_empty_and_non_finite_arrays(function):
    name = "kasha." + function.__name__
    for image, reference, fragments in (
            (xyz(0, 4), xyz(0, 4), ("image: is empty (0x4 pixels)",)),
            (xyz(), xyz(3, 0), ("reference: is empty (3x0 pixels)",)),
            (xyz(value=NAN), xyz(), ("image: pixel (0, 0) is not finite",)),
            (xyz(), xyz(value=-INF), ("reference: pixel (0, 0) is not finite",)),
            (xyz(), xyz(3, 5), ("reference: is 3x5 pixels, the image 3x4",)),
            (xyz()[:, :, :2], xyz(), ("image: expected an XYZ array of shape (height, width, 3)",)),
            ([["a"]], xyz(), ("image: expected an XYZ array",)),
            (xyz(), None, ("reference: expected an XYZ array",))):
        refused(lambda: function(image, reference), name + ": ", *fragments)
    one = xyz()
    one[2, 1, 0] = INF
    refused(lambda: function(xyz(), one), "pixel (1, 2) is not finite")
    function(xyz(), xyz(value=0.25))  # and a good pair is measured


def test_read_exr_memory_limit_is_checked(tmp_path):
    refused(lambda: kasha.read_exr(str(tmp_path / "x.exr"), memory_limit="-1G"), "kasha.read_exr: memory_limit")
