// Switching wavelength strategy never changes the converged image: on a small scene with two
// fluorophores under a UV-and-white sky and a narrow UV sun, at 8×8 pixels, images rendered with
// different strategies agree pixel by pixel within their combined standard errors (from
// independent batches). The scene has no caustics or small lights, so that per-pixel batch means
// are close to normal and their standard errors are trustworthy.
#include <gtest/gtest.h>

#include <cmath>

#include "scene/scene_loader.h"
#include "integrators/integrator_factory.h"
#include "integrators/render_loop.h"
#include "tests/support.h"

namespace kasha {
namespace {

constexpr int kRes = 8, kBatches = 16;

struct PixelStats {
  std::vector<test::BatchStats> v;  // per pixel and channel
};

const char* kScene = R"({
  "wavelength_range": [300, 830],
  "camera": {"position": [0, 1.2, -4], "look_at": [0, 0.6, 0], "up": [0, 1, 0], "fov": 40, "resolution": [8, 8]},
  "materials": {
    "uv_dye": {"type": "jung_fluorescent", "absorption": {"type": "box", "min": 340, "max": 420, "value": 0.8},
               "emission": {"type": "gaussian", "center": 520, "fwhm": 30}, "reflectance": 0.3, "c": 0.8, "Q": 0.9},
    "blue_dye": {"type": "jung_fluorescent", "absorption": {"type": "gaussian", "center": 450, "fwhm": 60, "peak": 0.7},
                 "emission": {"type": "gaussian", "center": 610, "fwhm": 40}, "reflectance": 0.4, "c": 0.6, "Q": 0.7},
    "floor": {"type": "lambertian", "reflectance": 0.6}
  },
  "shapes": [
    {"name": "a", "type": "sphere", "center": [-0.7, 0.6, 0], "radius": 0.6, "material": "uv_dye"},
    {"name": "b", "type": "sphere", "center": [0.7, 0.6, 0], "radius": 0.6, "material": "blue_dye"},
    {"name": "ground", "type": "rectangle", "center": [0, 0, 0], "u": [3, 0, 0], "v": [0, 0, 3], "material": "floor"}
  ],
  "lights": [
    {"type": "environment", "radiance": {"type": "tabulated", "wavelengths": [345, 350, 380, 385, 400, 405, 780, 785],
                                          "values": [0, 3, 3, 0, 0, 0.3, 0.3, 0]}},
    {"type": "distant", "direction": [0.3, -1, 0.4], "irradiance": {"type": "gaussian", "center": 365, "fwhm": 10, "peak": 4}}
  ]
})";

std::unique_ptr<Scene> testScene() { return loadSceneFromString(kScene, "two_dyes.json"); }

PixelStats renderBatches(const Scene& scene, const std::string& integratorName, const char* sensor,
                         const char* fluorescence, const char* light, int hero, const char* nee, int spp,
                         uint64_t seed) {
  RenderSettings s = scene.render;
  s.maxDepth = 8;
  s.wavelengths.sensor = parseWavelengthSpec(sensor);
  s.wavelengths.fluorescence = parseWavelengthSpec(fluorescence);
  s.wavelengths.light = parseWavelengthSpec(light);
  s.heroWavelengths = hero;
  s.wavelengths.nee = parseWavelengthSpec(nee);
  const std::unique_ptr<Integrator> integrator = makeIntegrator(integratorName, scene, s);
  std::vector<std::vector<double>> values(kRes * kRes * 3);
  for (int b = 0; b < kBatches; ++b) {
    Film film(kRes, kRes);
    RenderOptions opt;
    opt.spp = spp;
    opt.seed = seed + uint64_t(b);
    render(scene, *integrator, film, opt);
    for (int y = 0; y < kRes; ++y)
      for (int x = 0; x < kRes; ++x)
        for (int ch = 0; ch < 3; ++ch) values[size_t((y * kRes + x) * 3 + ch)].push_back(film.xyz(x, y)[ch]);
  }
  PixelStats p;
  for (const auto& v : values) p.v.push_back(test::batchStats(v));
  return p;
}

struct Variant {
  const char* integrator;
  const char* sensor;
  const char* fluorescence;
  const char* light;
  int spp;
  int hero = 1;
  const char* nee = "event";
};

void PrintTo(const Variant& v, std::ostream* os) {
  *os << v.integrator << " sensor=" << v.sensor << " fluorescence=" << v.fluorescence << " light=" << v.light << " hero=" << v.hero << " nee=" << v.nee;
}

class StrategySwitch : public ::testing::TestWithParam<Variant> {};

// z = (m_A − m_B) / √(se_A² + se_B²) per pixel and channel. With 16 batches each z follows about
// Student's t with 15 degrees of freedom: E[z²] = 15/13 ≈ 1.15 and Var[z²] ≈ 3.4, so over the
// 192 values the mean of z² has a standard error of about 0.13; it must stay below 1.15 + 4·0.13,
// and no single |z| may exceed 6 (a two-sided t₁₅ tail of 2·10⁻⁵ per value).
TEST_P(StrategySwitch, ImageAgreesWithTheDefaultPerPixel) {
  const Variant& v = GetParam();
  auto scene = testScene();
  const PixelStats a = renderBatches(*scene, "pt", "cmf", "material", "light", 1, "event", 128, 100);
  const PixelStats b = renderBatches(*scene, v.integrator, v.sensor, v.fluorescence, v.light, v.hero, v.nee, v.spp, 500);
  double sumZ2 = 0.0, maxZ = 0.0;
  int n = 0;
  for (size_t i = 0; i < a.v.size(); ++i) {
    const double se = std::sqrt(a.v[i].stderr_ * a.v[i].stderr_ + b.v[i].stderr_ * b.v[i].stderr_);
    if (se == 0.0) {
      EXPECT_EQ(a.v[i].mean, b.v[i].mean) << "value " << i;
      continue;
    }
    const double z = (a.v[i].mean - b.v[i].mean) / se;
    sumZ2 += z * z;
    maxZ = std::max(maxZ, std::abs(z));
    ++n;
  }
  ASSERT_GT(n, 150);  // the image is lit: the comparison has something to compare
  EXPECT_LT(sumZ2 / n, 1.15 + 4.0 * 0.13);
  EXPECT_LT(maxZ, 6.0);
}

INSTANTIATE_TEST_SUITE_P(
    Strategies, StrategySwitch,
    ::testing::Values(Variant{"pt", "ms-power:cmf,light", "material", "light", 64},
                      Variant{"pt", "yamamoto", "yamamoto", "light", 128},
                      Variant{"pt", "os-power:uniform,cmf", "mix:absorption,light", "light", 128},
                      Variant{"pt", "uniform", "uniform", "light", 128},
                      Variant{"bdpt-independent", "mix:cmf,uniform", "material", "mix:light,uniform", 32},
                      Variant{"pt", "cmf", "material", "light", 64, 4},
                      Variant{"pt", "yamamoto", "mix:absorption,light", "light", 64, 8},
                      Variant{"pt", "cmf", "material", "light", 128, 1, "light"},
                      Variant{"pt", "cmf", "uniform", "light", 128, 1, "mix:absorption,light"}),
    [](const ::testing::TestParamInfo<Variant>& info) { return "v" + std::to_string(info.index); });


}  // namespace
}  // namespace kasha
