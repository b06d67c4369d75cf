// Every wavelength strategy serves every fluorescent material (issue 11): on the UV Post-it scene
// (measured reradiation matrices and their Zhdanov fits under a 365 nm LED) and the glossy Cornell
// box (a coated FITC sphere), the path tracer with each strategy at the sensor, the fluorescent
// event and next-event estimation, and with hero wavelengths, agrees with the light tracer
// region by region within the standard errors of independent batches, at a low resolution. A
// strategy that misses part of the integrand is refused instead (tests/test_wavelength_strategies);
// plain `absorption` or `uniform` excitation on the UV Post-its is unbiased but too heavy-tailed
// (blue light of the measured pink note) for a test of this length.
#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <string>

#include "integrators/integrator_factory.h"
#include "scene/scene_loader.h"
#include "tests/region_batches.h"
#include "tests/support.h"

namespace kasha {
namespace {

constexpr int kW = 16, kH = 12, kBatches = 12;

struct Variant {
  const char* scene;
  const char* sensor = "cmf";
  const char* fluorescence = "material";
  const char* nee = "event";
  int hero = 1;
  int spp = 1024;
};

void PrintTo(const Variant& v, std::ostream* os) {
  *os << v.scene << " sensor=" << v.sensor << " fluorescence=" << v.fluorescence << " nee=" << v.nee
      << " hero=" << v.hero;
}

std::unique_ptr<Scene> lowRes(const std::string& name) {
  auto scene = loadScene(test::sourcePath("scenes/" + name));
  const Camera& c = scene->camera;
  scene->camera = Camera(c.position(), c.position() + c.forward(), Vec3(0, 1, 0), c.fovYDegrees(), kW, kH);
  return scene;
}

std::vector<test::BatchStats> quadrants(const Scene& scene, const std::string& integratorName, const RenderSettings& s,
                                        int spp) {
  const std::unique_ptr<Integrator> integrator = makeIntegrator(integratorName, scene, s);
  return test::regionBatches(
      scene, *integrator, kW, kH, 4, [](int x, int y) { return (2 * y / kH) * 2 + 2 * x / kW; }, spp, kBatches, 6151);
}

class StrategyScene : public ::testing::TestWithParam<Variant> {};

TEST_P(StrategyScene, AgreesWithTheLightTracerSlow) {
  const Variant& v = GetParam();
  const auto scene = lowRes(v.scene);
  RenderSettings s = scene->render;
  s.maxDepth = 8;
  static std::map<std::string, std::vector<test::BatchStats>> references;  // one light-traced reference per scene
  if (!references.count(v.scene)) references[v.scene] = quadrants(*scene, "lt", s, 2048);
  const std::vector<test::BatchStats>& ref = references[v.scene];
  s.wavelengths.sensor = parseWavelengthSpec(v.sensor);
  s.wavelengths.fluorescence = parseWavelengthSpec(v.fluorescence);
  s.wavelengths.nee = parseWavelengthSpec(v.nee);
  s.heroWavelengths = v.hero;
  const std::vector<test::BatchStats> pt = quadrants(*scene, "pt", s, v.spp);
  // 12 comparisons per variant: 4.5σ keeps the chance of a false alarm below 1e-4.
  test::expectRegionsAgree(ref, pt, 4.5, 0.1, 0.02);
}

INSTANTIATE_TEST_SUITE_P(
    Strategies, StrategyScene,
    ::testing::Values(Variant{"postit_uv.json"}, Variant{"postit_uv.json", "cmf", "yamamoto"},
                      Variant{"postit_uv.json", "uniform", "material"},
                      Variant{"postit_uv.json", "yamamoto", "mix:absorption,light"},
                      Variant{"postit_uv.json", "mix:emission,light", "mix:absorption,light"},
                      Variant{"postit_uv.json", "cmf", "mix:absorption,light", "mix:absorption,light"},
                      Variant{"postit_uv.json", "cmf", "material", "event", 4},
                      Variant{"postit_uv.json", "cmf", "yamamoto", "event", 4},
                      Variant{"cornell_glossy.json"}, Variant{"cornell_glossy.json", "cmf", "absorption"},
                      Variant{"cornell_glossy.json", "light", "yamamoto"},
                      Variant{"cornell_glossy.json", "mix:emission,light", "mix:emission,absorption"},
                      Variant{"cornell_glossy.json", "uniform", "mix:absorption,uniform", "light"},
                      Variant{"cornell_glossy.json", "cmf", "material", "event", 4},
                      Variant{"cornell_glossy.json", "yamamoto", "absorption", "event", 4}),
    [](const ::testing::TestParamInfo<Variant>& info) {
      return std::string(info.param.scene).substr(0, std::string(info.param.scene).find('.')) + "_v" +
             std::to_string(info.index);
    });

}  // namespace
}  // namespace kasha
