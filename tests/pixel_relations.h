#pragma once
// Renders compared pixel by pixel (the wrapper materials' statistical tests: a mask, a blend, on
// one sheet scene):
// an image that should be a linear combination Σ k_j·reference_j of others, judged by the mean
// over pixels of the difference, whose spread is the images' noise (the scene's structure
// cancels), within 4 standard errors.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "integrators/render_loop.h"
#include "scene/scene_loader.h"
#include "tests/integrator_names.h"

namespace kasha::test {

// The scene of the wrapper materials' tests: the sheet z = 0 (|x|, |y| ≤ 1, facing +z) made of
// `sheet`, seen from z = 2 at 12 × 12 pixels; `rest`: the remaining shapes and the lights,
// closing the shapes' array (kSheetPointLight, or further shapes with material "black").
inline std::string sheetScene(const std::string& sheet, const std::string& rest) {
  return R"({
  "camera": {"position": [0, 0, 2], "look_at": [0, 0, 0], "up": [0, 1, 0], "fov": 30, "resolution": [12, 12]},
  "render": {"max_depth": 4, "seed": 7},
  "materials": {"sheet": )" + sheet + R"(, "black": {"type": "lambertian", "reflectance": 0}},
  "shapes": [{"type": "rectangle", "corners": [[-1,-1,0], [1,-1,0], [1,1,0], [-1,1,0]], "material": "sheet"})" + rest + "}";
}
// A point light in front of the sheet, off its axis.
inline const std::string kSheetPointLight =
    R"(], "lights": [{"type": "point", "position": [0.3, 0.2, 1.5], "intensity": 1, "scale": 3}])";

// Y of every pixel of the JSON scene rendered by `integrator` at `spp` (seed 5).
inline std::vector<double> renderY(const std::string& json, const std::string& integrator, int spp) {
  const auto scene = loadSceneFromString(json, "scene.json");
  const std::unique_ptr<Integrator> integ = makeTestIntegrator(integrator, *scene, scene->render);
  Film film(scene->camera.width(), scene->camera.height());
  RenderOptions opt;
  opt.spp = spp;
  opt.seed = 5;
  render(*scene, *integ, film, opt);
  std::vector<double> y;
  for (int py = 0; py < film.height(); ++py)
    for (int px = 0; px < film.width(); ++px) y.push_back(film.xyz(px, py).y);
  return y;
}

inline double mean(const std::vector<double>& v) {
  double s = 0.0;
  for (const double x : v) s += x;
  return s / double(v.size());
}
// The standard error of the mean of independent values.
inline double standardError(const std::vector<double>& v) {
  const double m = mean(v);
  double s2 = 0.0;
  for (const double x : v) s2 += (x - m) * (x - m);
  return std::sqrt(s2 / double(v.size() - 1) / double(v.size()));
}

// got ≈ Σ k_j·reference_j pixel by pixel: the mean over pixels of d = got − Σ k_j·reference_j is
// 0 within 4 standard errors, and the test can tell a wrong combination: its error below
// `resolution` of the expectation.
inline void expectCombination(const std::vector<double>& got,
                              const std::vector<std::pair<double, const std::vector<double>*>>& terms,
                              const std::string& what, double resolution) {
  std::vector<double> d = got, expected(got.size(), 0.0);
  for (const auto& [k, reference] : terms)
    for (size_t i = 0; i < got.size(); ++i) expected[i] += k * (*reference)[i];
  for (size_t i = 0; i < got.size(); ++i) d[i] -= expected[i];
  const double expect = mean(expected), se = standardError(d);
  ASSERT_GT(expect, 0.0) << what;
  EXPECT_NEAR(mean(d), 0.0, 4.0 * se) << what << ": " << mean(got) / expect << " of the expectation (± " << se / expect
                                      << ")";
  EXPECT_LT(se, resolution * expect) << what << ": the test resolves the combination";
}

}  // namespace kasha::test
