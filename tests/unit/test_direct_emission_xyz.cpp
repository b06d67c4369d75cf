// Observer::xyz — the film's XYZ of a spectrum, ∫ W(λ)·L(λ) dλ — against independent integrals
// (Spectrum::integral of the colour-matching functions, a 0.01 nm midpoint sum), and the path
// tracer with lanes, which adds a directly seen area emitter's exact XYZ: every pixel of an image
// filled by a Gaussian emitter equals the closed form, which one-wavelength path tracing (a Monte
// Carlo estimate over λ) and BDPT with lanes (the exact value under its MIS weight, plus the light
// vertex seen by the camera) confirm within 4 standard errors.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "core/color.h"
#include "integrators/integrator_factory.h"
#include "integrators/render_loop.h"
#include "scene/scene_loader.h"
#include "tests/support.h"

namespace kasha {
namespace {

Vec3 midpointXyz(const Spectrum& L, WavelengthRange r) {
  const Observer& o = Observer::cie1931();
  glm::dvec3 sum(0.0);
  const int n = int((r.max - r.min) * 100.0f);
  for (int i = 0; i < n; ++i) {
    const float l = r.min + (float(i) + 0.5f) * (r.max - r.min) / float(n);
    sum += glm::dvec3(o.xbar(l), o.ybar(l), o.zbar(l)) * double(L(l));
  }
  return Vec3(sum * double(r.max - r.min) / double(n) / double(o.yIntegral));
}

TEST(ObserverXyz, ConstantBoxAndGaussianSpectra) {
  const Observer& o = Observer::cie1931();
  const Vec3 one = o.xyz(Spectrum::constant(1.0f), WavelengthRange{});
  EXPECT_NEAR(one.x, o.xbar.integral(360.0f, 830.0f) / o.yIntegral, 1e-5f);
  EXPECT_NEAR(one.y, 1.0f, 1e-5f);
  EXPECT_NEAR(one.z, o.zbar.integral(360.0f, 830.0f) / o.yIntegral, 1e-5f);
  for (const auto& [L, range] : {std::pair{Spectrum::box(500.3f, 560.7f, 2.0f), WavelengthRange{}},
                                 std::pair{Spectrum::gaussian(455.0f, 30.0f), WavelengthRange{400.0f, 700.0f}}}) {
    const Vec3 exact = o.xyz(L, range), sum = midpointXyz(L, range);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(exact[c], sum[c], 2e-4f * std::max(1.0f, std::abs(sum[c]))) << c;
  }
}

std::unique_ptr<Scene> emitterFillingTheView() {
  const nlohmann::json j = nlohmann::json::parse(R"({
    "wavelength_range": [360, 830],
    "render": {"spp": 4, "max_depth": 4},
    "camera": {"position": [0, 0, 0], "look_at": [0, 0, 1], "up": [0, 1, 0], "fov": 30, "resolution": [8, 8]},
    "spectra": {"blue": {"type": "gaussian", "center": 455, "fwhm": 30}},
    "materials": {"black": {"type": "lambertian", "reflectance": 0}},
    "shapes": [{"name": "panel", "type": "rectangle", "corners": [[-5, -5, 1], [5, -5, 1], [5, 5, 1], [-5, 5, 1]],
                "material": "black", "emission": {"radiance": "blue", "scale": 3, "two_sided": true}}]
  })");
  return loadSceneFromJson(j, test::sourcePath("scenes/emitter.json"));
}

TEST(DirectEmission, LanesAddTheExactXyzOfASeenEmitter) {
  const auto scene = emitterFillingTheView();
  const AreaEmission& e = *scene->shapes[0].emission;
  const Vec3 exact = Observer::cie1931().xyz(e.radiance, scene->range) * e.scale;
  RenderSettings lanes = scene->render;
  lanes.heroWavelengths = 4;
  const std::unique_ptr<Integrator> pt = makeIntegrator("pt", *scene, lanes);
  Film film(8, 8);
  RenderOptions opt;
  opt.spp = 4;
  render(*scene, *pt, film, opt);
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 8; ++x)
      for (int c = 0; c < 3; ++c) EXPECT_NEAR(film.xyz(x, y)[c], exact[c], 1e-5f * exact.y) << x << " " << y << " " << c;

  // One wavelength per path estimates the same integral over λ, and so does BDPT with lanes (its
  // camera hitting the light adds the exact XYZ with its MIS weight, the light vertex seen by the
  // camera the rest).
  for (const auto& [name, lanesPerPath] : {std::pair{"pt", 1}, std::pair{"bdpt-shared", 4}}) {
    RenderSettings settings = scene->render;
    settings.heroWavelengths = lanesPerPath;
    const std::unique_ptr<Integrator> other = makeIntegrator(name, *scene, settings);
    std::vector<double> batches[3];
    for (int b = 0; b < 16; ++b) {
      Film f(8, 8);
      opt.spp = 64;
      opt.seed = uint64_t(b + 1);
      render(*scene, *other, f, opt);
      Vec3 mean(0.0f);
      for (int y = 0; y < 8; ++y)
        for (int x = 0; x < 8; ++x) mean += f.xyz(x, y) / 64.0f;
      for (int c = 0; c < 3; ++c) batches[c].push_back(mean[c]);
    }
    for (int c = 0; c < 3; ++c) {
      const test::BatchStats s = test::batchStats(batches[c]);
      EXPECT_LT(s.stderr_, 0.02 * std::abs(s.mean)) << name << " " << c;
      // Plus the film's float rounding: BDPT's estimate here is almost exactly the exact value.
      EXPECT_NEAR(s.mean, exact[c], 4.0 * s.stderr_ + 1e-5 * std::abs(exact[c])) << name << " " << c;
    }
  }
}

}  // namespace
}  // namespace kasha
