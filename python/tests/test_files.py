"""Files read and written from Python follow kasha's rules (docs/reliability.md "Files in and out"): regular
files only, strict JSON, outputs checked before the first sample, decoded images counted against
the memory limit."""
import json
import os

import numpy as np
import pytest

import kasha
from conftest import REPO, furnace_dict


def test_scene_files_are_read_like_the_command_line(tmp_path):
    fifo = tmp_path / "scene.json"
    os.mkfifo(fifo)  # opening it must not block, reading it is refused
    with pytest.raises(kasha.InputError, match="scene.json: cannot open scene file .*not a regular file"):
        kasha.Scene(str(fifo))
    twice = tmp_path / "twice.json"
    twice.write_text('{"render": {"spp": 1, "spp": 2}}')
    with pytest.raises(kasha.InputError, match="twice.json: /render/spp: duplicate key 'spp'"):
        kasha.Scene(str(twice))


def test_outputs_are_checked_before_the_first_sample(tmp_path):
    scene = kasha.Scene.from_dict(furnace_dict(resolution=4, spp=4))
    passes = []
    for bad, reason in ((tmp_path / "missing" / "out.exr", "missing"), (tmp_path / "out.png", r"\.exr")):
        with pytest.raises(kasha.InputError, match=reason):
            kasha.render(scene, output=str(bad), progress=lambda *a: passes.append(a))
        assert not bad.exists()
    assert passes == []  # refused before rendering
    source = tmp_path / "scene.exr"  # a JSON scene under a name an output could have
    source.write_text(json.dumps(furnace_dict(resolution=4, spp=4)))
    scene = kasha.Scene(str(source))
    with pytest.raises(kasha.InputError, match="scene.exr: output: is one of the inputs"):
        kasha.render(scene, output=str(source))
    assert json.loads(source.read_text())["render"]["spp"] == 4
    # A written output leaves no temporary file beside it.
    kasha.render(scene, output=str(tmp_path / "ok.exr"), spectral_bins=4)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["ok.exr", "scene.exr"]


def test_read_exr_refuses_what_kasha_metrics_refuses(tmp_path):
    with pytest.raises(kasha.InputError, match="not a regular file"):
        kasha.read_exr(str(tmp_path))
    out = str(tmp_path / "bins.exr")
    kasha.render(kasha.Scene.from_dict(furnace_dict(resolution=8, spp=1)), output=out, spectral_bins=64)
    assert kasha.read_exr(out)["spectral"].shape == (8, 8, 64)
    # 64 bins × 4 bytes per pixel are over a 4 KiB limit at 8x8 pixels.
    with pytest.raises(kasha.InputError, match="bins.exr: .*memory limit"):
        kasha.read_exr(out, memory_limit="4K")


def test_mitsuba_scene_from_python():
    scene = kasha.Scene(os.path.join(REPO, "scenes", "mitsuba", "cornell_box.xml"))
    assert scene.path.endswith("cornell_box.xml") and scene.materials
    scene.set("/camera/resolution", [8, 6])
    result = kasha.render(scene, spp=1, max_depth=2)
    assert result["xyz"].shape == (6, 8, 3) and np.all(np.isfinite(result["xyz"]))


MITSUBA_WITH_PARAMETERS = """<scene version="3.0.0">
  <integrator type="$integrator"/>
  <sensor type="perspective"><float name="fov" value="40"/>
    <film type="hdrfilm"><integer name="width" value="$res"/><integer name="height" value="$res"/></film>
  </sensor>
  <emitter type="point"><point name="position" x="0" y="3" z="0"/><spectrum name="intensity" value="1"/></emitter>
  <shape type="rectangle"><bsdf type="diffuse"/></shape>
</scene>
"""


def test_mitsuba_defaults_and_the_scenes_integrator(tmp_path):
    path = tmp_path / "params.xml"
    path.write_text(MITSUBA_WITH_PARAMETERS)
    scene = kasha.Scene(str(path), defaults={"integrator": "ptracer", "res": 4})
    assert scene.get("/render/integrator") == "lt"
    assert scene.get("/camera/resolution") == [4, 4]
    # The scene's integrator unless kasha.render names one.
    assert kasha.render(scene, spp=1, threads=1)["stats"]["integrator"] == "lt"
    assert kasha.render(scene, integrator="pt", spp=1, threads=1)["stats"]["integrator"] == "pt"
    with pytest.raises(kasha.InputError, match=r"parameter '\$res' has no <default>"):
        kasha.Scene(str(path), defaults={"integrator": "path"})
    with pytest.raises(kasha.InputError, match="kasha.Scene: defaults: 'r-s' is not a parameter name"):
        kasha.Scene(str(path), defaults={"r-s": 4})
    with pytest.raises(kasha.InputError, match="sets parameters of a Mitsuba XML scene"):
        kasha.Scene(os.path.join(REPO, "scenes", "jung18_fig1.json"), defaults={"spp": 4})
    with pytest.raises(kasha.InputError, match="kasha.Scene: defaults: expected str, int or float values"):
        kasha.Scene(str(path), defaults={"res": [4]})


def test_mitsuba_search_paths(tmp_path):
    (tmp_path / "shared" / "meshes").mkdir(parents=True)
    (tmp_path / "shared" / "meshes" / "tri.obj").write_text("v -1 -1 0\nv 1 -1 0\nv -1 1 0\nf 1 2 3\n")
    path = tmp_path / "uses_shared.xml"
    path.write_text(MITSUBA_WITH_PARAMETERS.replace(
        '<shape type="rectangle">', '<shape type="obj"><string name="filename" value="meshes/tri.obj"/>'))
    with pytest.raises(kasha.InputError, match="meshes/tri.obj: cannot open mesh file"):
        kasha.render(kasha.Scene(str(path), defaults={"integrator": "path", "res": 4}), spp=1, threads=1)
    scene = kasha.Scene(str(path), defaults={"integrator": "path", "res": 4}, search_paths=[str(tmp_path / "shared")])
    assert scene.get("/shapes/0/file") == str(tmp_path / "shared" / "meshes" / "tri.obj")
    with pytest.raises(kasha.InputError, match="kasha.Scene: search_paths: .*: no such directory"):
        kasha.Scene(str(path), search_paths=[str(tmp_path / "none")])
    with pytest.raises(kasha.InputError, match="kasha.Scene: search_paths: expected a list or None"):
        kasha.Scene(str(path), search_paths=str(tmp_path))
