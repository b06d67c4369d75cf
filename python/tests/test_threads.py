"""A Scene edited or rendered again while a render of it runs, from other threads or from the
progress callback: every render is of the scene as it was when the render started, bit for bit its
single-threaded render (python/py_scene.h, docs/python.md "Threads"). Before, a second render freed
the loaded scene under the first."""
import threading

import numpy as np
import pytest

import kasha
from conftest import furnace_dict

# The versions of the scene the edits switch between: its material's c, whose images differ.
VERSIONS = (0.0, 0.5, 1.0)
SPP = 32  # 16 a pass at 64x64 pixels (integrators/render_loop.h): two passes, two callbacks


def new_scene():
    return kasha.Scene.from_dict(furnace_dict(c=VERSIONS[0], resolution=64, spp=SPP, seed=11))


@pytest.fixture(scope="module")
def references():
    """Each version rendered alone on one thread."""
    images = {}
    for c in VERSIONS:
        scene = new_scene()
        scene.set("/materials/wall/c", c)
        images[c] = kasha.render(scene, threads=1)["xyz"]
    for a in VERSIONS:
        for b in VERSIONS:
            assert a == b or not np.array_equal(images[a], images[b])  # an image tells its version
    return images


def version_of(image, references):
    """The version whose single-threaded render `image` equals bit for bit, or None."""
    return next((c for c, ref in references.items() if np.array_equal(image, ref)), None)


def test_a_render_from_the_progress_callback_leaves_the_running_one_alone(references):
    # Deterministic: the outer render (c = 0) is between its passes when the callback edits the
    # scene and renders the edited scene, which replaces the scene the module keeps.
    scene = new_scene()
    inner = []

    def progress(spp, seconds, total):
        if not inner:
            scene.set("/materials/wall/c", VERSIONS[2])
            inner.append(kasha.render(scene)["xyz"])
            scene.set("/materials/wall/c", VERSIONS[1])

    outer = kasha.render(scene, progress=progress)["xyz"]
    assert version_of(outer, references) == VERSIONS[0]
    assert version_of(inner[0], references) == VERSIONS[2]
    assert version_of(kasha.render(scene)["xyz"], references) == VERSIONS[1]  # the next render sees the edit


def test_two_threads_render_while_a_third_and_the_callbacks_edit(references):
    scene = new_scene()
    lock = threading.Lock()
    running = [0]            # renders in flight
    edits_meanwhile = [0]    # edits by the editing thread while one was
    callback_edits = [0]
    images, errors = [], []
    done = threading.Event()

    def edit(i):
        scene.set("/materials/wall/c", VERSIONS[i % len(VERSIONS)])

    def editor():
        i = 0
        try:
            while not done.is_set():
                edit(i)
                with lock:
                    edits_meanwhile[0] += running[0] > 0
                i += 1
                done.wait(0.002)
        except Exception as e:  # an edit may only be refused with InputError; none is expected
            errors.append(e)

    def renderer(k):
        def progress(spp, seconds, total):
            edit(k + spp // 16)
            with lock:
                callback_edits[0] += 1

        try:
            for _ in range(2):
                with lock:
                    running[0] += 1
                try:
                    images.append(kasha.render(scene, progress=progress)["xyz"])
                finally:
                    with lock:
                        running[0] -= 1
        except Exception as e:
            errors.append(e)

    threads = [threading.Thread(target=renderer, args=(k,)) for k in (0, 1)]
    edits = threading.Thread(target=editor)
    edits.start()
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    done.set()
    edits.join()
    assert not errors, errors
    assert len(images) == 4
    assert edits_meanwhile[0] > 0 and callback_edits[0] >= 4 * 2
    for image in images:
        assert version_of(image, references) is not None
