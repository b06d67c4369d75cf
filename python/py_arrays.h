#pragma once
// numpy arrays of kasha's images for the Python module: XYZ and linear sRGB as (height, width, 3),
// spectral bins as (height, width, bins), all float32, row 0 at the top.
#include <pybind11/numpy.h>

#include "core/film.h"
#include "core/image_input.h"
#include "core/spectral_exr.h"
#include "core/spectral_film.h"

namespace kasha::python {

pybind11::array_t<float> xyzArray(const Film& film);
pybind11::array_t<float> xyzArray(const XyzImage& image);
// Linear sRGB (core/color.h) of an XYZ array.
pybind11::array_t<float> rgbArray(const pybind11::array_t<float>& xyz);
pybind11::array_t<float> spectralArray(const SpectralFilm& film);
pybind11::array_t<float> spectralArray(const SpectralImage& image);
// A (height, width, 3) array as an XyzImage; ValueError naming `what` for any other shape.
XyzImage toXyzImage(const pybind11::array_t<float, pybind11::array::c_style | pybind11::array::forcecast>& a,
                    const char* what);

}  // namespace kasha::python
