"""Renders release the GIL, stop on Ctrl-C with the partial image, and report progress."""
import os
import signal
import threading
import time

import numpy as np

import kasha
from conftest import furnace_dict


def long_scene():
    return kasha.Scene.from_dict(furnace_dict(resolution=32, spp=1 << 20))


def test_ctrl_c_raises_keyboard_interrupt_with_the_partial_result():
    scene = long_scene()
    timer = threading.Timer(0.5, lambda: os.kill(os.getpid(), signal.SIGINT))
    start = time.monotonic()
    timer.start()
    try:
        kasha.render(scene, time=30)
        raise AssertionError("the render was not interrupted")
    except kasha.RenderInterrupted as e:
        assert isinstance(e, KeyboardInterrupt)
        stats = e.result["stats"]
        assert stats["interrupted"] and 0 < stats["spp"] < 1 << 20
        assert np.all(np.isfinite(e.result["xyz"])) and e.result["xyz"].mean() > 0
    finally:
        timer.cancel()
    assert time.monotonic() - start < 10  # stopped at a pass boundary, not at the time budget


def test_progress_callback_and_its_exceptions():
    scene = kasha.Scene.from_dict(furnace_dict(resolution=32, spp=256))  # 64 spp a pass
    calls = []
    kasha.render(scene, progress=lambda spp, t, total: calls.append((spp, t, total)))
    assert len(calls) > 1 and calls[-1][0] == 256
    assert all(a[0] < b[0] for a, b in zip(calls, calls[1:]))

    def stop(spp, t, total):
        raise KeyboardInterrupt

    try:
        kasha.render(scene, progress=stop)
        raise AssertionError("not interrupted")
    except kasha.RenderInterrupted as e:
        assert 0 < e.result["stats"]["spp"] < 256

    def fail(spp, t, total):
        raise RuntimeError("from the callback")

    try:
        kasha.render(scene, progress=fail)
        raise AssertionError("the callback's exception was lost")
    except RuntimeError as e:
        assert "from the callback" in str(e)


def test_the_gil_is_released_while_rendering():
    scene = long_scene()
    ticks, done = [], threading.Event()

    def count():
        while not done.is_set():
            ticks.append(time.monotonic())
            time.sleep(0.001)

    thread = threading.Thread(target=count)
    thread.start()
    try:
        start = time.monotonic()
        kasha.render(scene, time=1.0)
        end = time.monotonic()
    finally:
        done.set()
        thread.join()
    during = [t for t in ticks if start + 0.2 < t < end - 0.2]
    assert end - start > 0.9
    assert len(during) > 50, len(during)
