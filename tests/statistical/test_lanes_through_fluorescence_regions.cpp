// Issue 12's criterion for lanes through fluorescence: the path tracer with its 4 lanes carried
// through fluorescent events agrees region by region (4 × 4 regions, X, Y, Z) with one wavelength
// per path (`--hero 1`) on the UV Post-it scene (measured reradiation matrices under a 365 nm LED)
// and the Cornell box under a UV LED, within 4 standard errors of independent batches.
#include <gtest/gtest.h>

#include "integrators/integrator_factory.h"
#include "scene/scene_loader.h"
#include "tests/region_batches.h"
#include "tests/support.h"

namespace kasha {
namespace {

constexpr int kRes = 16, kRegions = 4;

std::vector<test::BatchStats> regions(const Scene& scene, int lanes, int spp) {
  RenderSettings s = scene.render;
  s.heroWavelengths = lanes;
  const std::unique_ptr<Integrator> pt = makeIntegrator("pt", scene, s);
  EXPECT_EQ(pt->lanes(), lanes);
  return test::regionBatches(
      scene, *pt, kRes, kRes, kRegions * kRegions,
      [](int x, int y) { return (y * kRegions / kRes) * kRegions + x * kRegions / kRes; }, spp, 16, 7919);
}

class LanesThroughFluorescenceSlow : public ::testing::TestWithParam<const char*> {};

TEST_P(LanesThroughFluorescenceSlow, AgreeWithOneWavelengthRegionByRegion) {
  auto scene = loadScene(test::sourcePath(std::string("scenes/") + GetParam()));
  test::useSquareCamera(*scene, kRes);
  const std::vector<test::BatchStats> one = regions(*scene, 1, 512), lanes = regions(*scene, 4, 128);
  test::expectRegionsAgree(one, lanes, 4.0, 0.1, 0.02);
}

INSTANTIATE_TEST_SUITE_P(Scenes, LanesThroughFluorescenceSlow, ::testing::Values("postit_uv.json", "cornell_uv.json"),
                         [](const ::testing::TestParamInfo<const char*>& info) {
                           std::string n = info.param;
                           return n.substr(0, n.find('.'));
                         });

}  // namespace
}  // namespace kasha
