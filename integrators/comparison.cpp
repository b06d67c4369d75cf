#include "integrators/comparison.h"

#include <cmath>
#include <stdexcept>

#include "integrators/render_job.h"

namespace kasha {

XyzImage filmToXyz(const Film& film) {
  XyzImage img;
  img.width = film.width();
  img.height = film.height();
  for (int y = 0; y < film.height(); ++y)
    for (int x = 0; x < film.width(); ++x) img.pixels.push_back(film.xyz(x, y));
  return img;
}

namespace {

struct PixelError {
  double squared = 0.0;   // Σ over X, Y, Z of (x − ref)²
  double relative = 0.0;  // Σ over X, Y, Z of (x − ref)² / (ref² + 1e-2)
};

PixelError pixelError(const Vec3& v, const Vec3& r) {
  PixelError e;
  for (int c = 0; c < 3; ++c) {
    const double d = double(v[c]) - double(r[c]);
    e.squared += d * d;
    e.relative += d * d / (double(r[c]) * r[c] + 1e-2);
  }
  return e;
}

void requireSameSize(const XyzImage& image, const XyzImage& ref) {
  if (image.width != ref.width || image.height != ref.height)
    throw std::invalid_argument("the reference is " + std::to_string(ref.width) + "x" + std::to_string(ref.height) +
                                ", the image " + std::to_string(image.width) + "x" + std::to_string(image.height));
}

}  // namespace

ImageError compareImages(const XyzImage& image, const XyzImage& ref) {
  requireSameSize(image, ref);
  double se = 0.0, rel = 0.0;
  for (size_t i = 0; i < ref.pixels.size(); ++i) {
    const PixelError e = pixelError(image.pixels[i], ref.pixels[i]);
    se += e.squared;
    rel += e.relative;
  }
  const double n = 3.0 * double(ref.pixels.size());
  return {std::sqrt(se / n), rel / n};
}

ImageError compareToReference(const Film& film, const XyzImage& ref) { return compareImages(filmToXyz(film), ref); }

std::vector<float> relativeErrorMap(const XyzImage& image, const XyzImage& ref) {
  requireSameSize(image, ref);
  std::vector<float> map(ref.pixels.size());
  for (size_t i = 0; i < map.size(); ++i) map[i] = float(pixelError(image.pixels[i], ref.pixels[i]).relative / 3.0);
  return map;
}

std::vector<ComparisonRow> compareIntegrators(const Scene& scene, const std::vector<std::string>& integrators,
                                              const RenderSettings& settings, int threads, const XyzImage& reference) {
  std::vector<ComparisonRow> rows;
  for (const std::string& name : integrators) {
    RenderJobOptions options;
    options.integrator = name;
    options.settings = settings;
    options.threads = threads;
    RenderJob job(scene, std::move(options));
    job.run();
    ComparisonRow row;
    row.integrator = name;
    row.stats = job.stats();
    row.error = compareToReference(job.film(), reference);
    rows.push_back(row);
  }
  return rows;
}

}  // namespace kasha
