#include "python/py_arrays.h"

#include <climits>
#include <string>

#include "core/color.h"
#include "core/error.h"

namespace py = pybind11;

namespace kasha::python {

py::array_t<float> xyzArray(const Film& film) {
  py::array_t<float> a({py::ssize_t(film.height()), py::ssize_t(film.width()), py::ssize_t(3)});
  auto v = a.mutable_unchecked<3>();
  for (int y = 0; y < film.height(); ++y)
    for (int x = 0; x < film.width(); ++x) {
      const Vec3 c = film.xyz(x, y);
      for (int k = 0; k < 3; ++k) v(y, x, k) = c[k];
    }
  return a;
}

py::array_t<float> xyzArray(const XyzImage& image) {
  py::array_t<float> a({py::ssize_t(image.height), py::ssize_t(image.width), py::ssize_t(3)});
  auto v = a.mutable_unchecked<3>();
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x)
      for (int k = 0; k < 3; ++k) v(y, x, k) = image.pixels[size_t(y) * image.width + x][k];
  return a;
}

py::array_t<float> rgbArray(const py::array_t<float>& xyz) {
  const auto in = xyz.unchecked<3>();
  py::array_t<float> a({in.shape(0), in.shape(1), py::ssize_t(3)});
  auto out = a.mutable_unchecked<3>();
  for (py::ssize_t y = 0; y < in.shape(0); ++y)
    for (py::ssize_t x = 0; x < in.shape(1); ++x) {
      const Vec3 rgb = xyzToLinearSrgb(Vec3(in(y, x, 0), in(y, x, 1), in(y, x, 2)));
      for (int k = 0; k < 3; ++k) out(y, x, k) = rgb[k];
    }
  return a;
}

py::array_t<float> spectralArray(const SpectralFilm& film) {
  const int n = film.bins().count;
  py::array_t<float> a({py::ssize_t(film.height()), py::ssize_t(film.width()), py::ssize_t(n)});
  auto v = a.mutable_unchecked<3>();
  for (int y = 0; y < film.height(); ++y)
    for (int x = 0; x < film.width(); ++x)
      for (int b = 0; b < n; ++b) v(y, x, b) = film.value(x, y, b);
  return a;
}

py::array_t<float> spectralArray(const SpectralImage& image) {
  const py::ssize_t n = py::ssize_t(image.wavelengths.size());
  py::array_t<float> a({py::ssize_t(image.height), py::ssize_t(image.width), n});
  std::copy(image.values.begin(), image.values.end(), a.mutable_data());
  return a;
}

XyzImage toXyzImage(const py::handle& value, const Argument& arg) {
  using Array = py::array_t<float, py::array::c_style | py::array::forcecast>;
  const Array a = Array::ensure(value);  // null if numpy cannot make float32 of it
  const std::string where = std::string(arg.function) + ": " + arg.name;
  if (!a || a.ndim() != 3 || a.shape(2) != 3)
    throw InputError(where, "", "expected an XYZ array of shape (height, width, 3)");
  const std::string size = std::to_string(a.shape(0)) + "x" + std::to_string(a.shape(1));
  if (a.shape(0) == 0 || a.shape(1) == 0) throw InputError(where, "", "is empty (" + size + " pixels)");
  if (a.shape(0) > INT_MAX || a.shape(1) > INT_MAX) throw InputError(where, "", size + " pixels are more than an image holds");
  XyzImage img;
  img.height = int(a.shape(0));
  img.width = int(a.shape(1));
  const auto v = a.unchecked<3>();
  img.pixels.resize(size_t(img.width) * img.height);
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x) img.pixels[size_t(y) * img.width + x] = Vec3(v(y, x, 0), v(y, x, 1), v(y, x, 2));
  requireFinitePixels(img, where);
  return img;
}

}  // namespace kasha::python
