// Wavelength lanes in BDPT (docs/bdpt-mis.md §10). On scenes/validation/box_spectra_lanes.json —
// walls that reflect in disjoint bands (zero elsewhere), a panel emitting in a band that overlaps
// both, a rough metal patch (lanes kept) and a dispersive frosted sphere (lanes ended on arrival) —
// bdpt-shared, bdpt and bdpt-independent with 4 lanes, and bdpt-shared with one and seven, agree
// with one-wavelength path tracing region by region within 4.5 standard errors (bdpt-independent's
// weights against its own t = 1 differ from lane to lane). Every BDPT variant defaults to 4 lanes,
// and their number is what the statistics report.
#include <gtest/gtest.h>

#include "integrators/integrator_factory.h"
#include "integrators/wavelength_lanes.h"
#include "scene/scene_loader.h"
#include "tests/region_batches.h"
#include "tests/support.h"

namespace kasha {
namespace {

constexpr int kRes = 16, kRegions = 2;  // 2×2 regions of a 16×16 image

std::unique_ptr<Scene> boxSpectra() {
  auto scene = loadScene(test::sourcePath("scenes/validation/box_spectra_lanes.json"));
  const Camera& c = scene->camera;
  scene->camera = Camera(c.position(), c.position() + c.forward(), Vec3(0, 1, 0), c.fovYDegrees(), kRes, kRes);
  return scene;
}

std::vector<test::BatchStats> estimate(const Scene& scene, const std::string& name, int lanes, int spp) {
  RenderSettings settings = scene.render;
  settings.heroWavelengths = lanes;
  const std::unique_ptr<Integrator> integrator = makeIntegrator(name, scene, settings);
  EXPECT_EQ(integrator->lanes(), lanes) << name;
  return test::regionBatches(
      scene, *integrator, kRes, kRes, kRegions * kRegions,
      [](int x, int y) { return (y * kRegions / kRes) * kRegions + x * kRegions / kRes; }, spp, 12, 7919);
}

class BdptLanesSlow : public ::testing::TestWithParam<std::pair<const char*, int>> {};

TEST_P(BdptLanesSlow, AgreeWithOneWavelengthPathTracingRegionByRegion) {
  const auto [name, lanes] = GetParam();
  const auto scene = boxSpectra();
  static const std::vector<test::BatchStats> ref = estimate(*scene, "pt", 1, 3072);
  const std::vector<test::BatchStats> other = estimate(*scene, name, lanes, 384);
  for (size_t i = 0; i < ref.size(); ++i) {
    const double sigma = std::hypot(ref[i].stderr_, other[i].stderr_);
    EXPECT_LT(sigma, 0.06 * std::abs(ref[i].mean)) << "too noisy to compare, region/channel " << i;
    EXPECT_NEAR(other[i].mean, ref[i].mean, 4.5 * sigma) << name << " with " << lanes << " lanes, region/channel " << i;
  }
}

INSTANTIATE_TEST_SUITE_P(Estimators, BdptLanesSlow,
                         ::testing::Values(std::make_pair("bdpt-shared", 4), std::make_pair("bdpt", 4),
                                           std::make_pair("bdpt-shared", 1), std::make_pair("bdpt-shared", 7),
                                           std::make_pair("bdpt-independent", 4)),
                         [](const auto& info) {
                           std::string n = info.param.first;
                           for (char& ch : n)
                             if (ch == '-') ch = '_';
                           return n + "_" + std::to_string(info.param.second) + "_lanes";
                         });

TEST(BdptLaneDefaults, FourInEveryVariant) {
  const auto plain = boxSpectra();
  const auto fluorescent = loadScene(test::sourcePath("scenes/cornell_uv.json"));
  RenderSettings automatic = plain->render;
  automatic.heroWavelengths = kAutoLanes;
  for (const auto* scene : {plain.get(), fluorescent.get()})
    for (const char* name : {"bdpt", "bdpt-shared", "bdpt-independent"})
      EXPECT_EQ(makeIntegrator(name, *scene, automatic)->lanes(), 4) << name;
  RenderSettings tooMany = automatic;
  tooMany.heroWavelengths = kMaxLanes + 1;
  EXPECT_THROW(makeIntegrator("bdpt", *fluorescent, tooMany), std::invalid_argument);
}

}  // namespace
}  // namespace kasha
