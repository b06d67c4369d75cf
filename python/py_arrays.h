#pragma once
// numpy arrays of kasha's images for the Python module: XYZ and linear sRGB as (height, width, 3),
// spectral bins as (height, width, bins), all float32, row 0 at the top.
#include <pybind11/numpy.h>

#include "core/film.h"
#include "core/image_input.h"
#include "core/spectral_exr.h"
#include "core/spectral_film.h"
#include "python/py_arguments.h"

namespace kasha::python {

pybind11::array_t<float> xyzArray(const Film& film);
pybind11::array_t<float> xyzArray(const XyzImage& image);
// Linear sRGB (core/color.h) of an XYZ array.
pybind11::array_t<float> rgbArray(const pybind11::array_t<float>& xyz);
pybind11::array_t<float> spectralArray(const SpectralFilm& film);
pybind11::array_t<float> spectralArray(const SpectralImage& image);
// An array of shape (height, width, 3), at least one pixel, every value finite (read as float32), as
// an XyzImage; anything else raises InputError naming `arg`.
XyzImage toXyzImage(const pybind11::handle& value, const Argument& arg);

}  // namespace kasha::python
