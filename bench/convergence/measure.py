"""Errors of the harness's renders against their reference.

In-process (the default when the Python module `kasha` is built in the build directory): each
reference EXR is read once, each render's EXR once, and kasha.metrics / kasha.error_map (the same
integrators/comparison.h as `kasha metrics`) measure them without a subprocess per render. With
--cli, or without the module, every measurement runs `kasha metrics` (kasha_cli.metrics).
"""
import importlib
import os
import sys

import numpy as np

import kasha_cli


def write_pfm(path, values):
    """A greyscale little-endian Portable Float Map, bottom row first (as `kasha metrics --error-map`)."""
    h, w = values.shape
    with open(path, "wb") as f:
        f.write(f"Pf\n{w} {h}\n-1.0\n".encode())
        f.write(np.ascontiguousarray(values[::-1], dtype="<f4").tobytes())


class InProcess:
    """Metrics through the module; references cached by path (the harness renders each one once)."""

    def __init__(self, module):
        self.kasha = module
        self.references = {}

    def __call__(self, image, reference, error_map=None):
        if reference not in self.references:
            self.references[reference] = self.kasha.read_exr(reference)["xyz"]
        ref = self.references[reference]
        img = self.kasha.read_exr(image)["xyz"]
        m = self.kasha.metrics(img, ref)
        if error_map:
            write_pfm(error_map, self.kasha.error_map(img, ref))
        return m


def metrics_function(binary, build_dir, use_cli):
    """The function (image, reference, error_map=None) -> {"rmse", "relmse"} the harness uses, and
    which path it takes ("module" or "cli")."""
    if not use_cli:
        sys.path.insert(0, os.path.join(build_dir, "python"))
        try:
            return InProcess(importlib.import_module("kasha")), "module"
        except ImportError:
            sys.path.pop(0)
    return (lambda image, reference, error_map=None: kasha_cli.metrics(binary, image, reference, error_map)), "cli"
