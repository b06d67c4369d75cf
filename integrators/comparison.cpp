#include "integrators/comparison.h"

#include <cmath>
#include <stdexcept>

#include "integrators/integrator_factory.h"

namespace kasha {

XyzImage filmToXyz(const Film& film) {
  XyzImage img;
  img.width = film.width();
  img.height = film.height();
  for (int y = 0; y < film.height(); ++y)
    for (int x = 0; x < film.width(); ++x) img.pixels.push_back(film.xyz(x, y));
  return img;
}

ImageError compareToReference(const Film& film, const XyzImage& ref) {
  if (film.width() != ref.width || film.height() != ref.height)
    throw std::invalid_argument("the reference is " + std::to_string(ref.width) + "x" + std::to_string(ref.height) +
                                ", the render " + std::to_string(film.width()) + "x" + std::to_string(film.height()));
  double se = 0.0, rel = 0.0;
  size_t i = 0;
  for (int y = 0; y < film.height(); ++y)
    for (int x = 0; x < film.width(); ++x, ++i) {
      const Vec3 v = film.xyz(x, y), r = ref.pixels[i];
      for (int c = 0; c < 3; ++c) {
        const double d = double(v[c]) - double(r[c]);
        se += d * d;
        rel += d * d / (double(r[c]) * r[c] + 1e-2);
      }
    }
  const double n = 3.0 * double(ref.pixels.size());
  return {std::sqrt(se / n), rel / n};
}

std::vector<ComparisonRow> compareIntegrators(const Scene& scene, const std::vector<std::string>& integrators,
                                              const RenderOptions& options, const XyzImage& reference) {
  std::vector<ComparisonRow> rows;
  for (const std::string& name : integrators) {
    const std::unique_ptr<Integrator> integrator = makeIntegrator(name, scene, scene.render);
    Film film(scene.camera.width(), scene.camera.height());
    ComparisonRow row;
    row.integrator = name;
    row.stats = render(scene, *integrator, film, options);
    row.error = compareToReference(film, reference);
    rows.push_back(row);
  }
  return rows;
}

}  // namespace kasha
