// docs/validation.md §4: on the Cornell fluorescent scenes (white light; UV + white; glossy materials:
// coated fluorescent sphere, frosted glass, brushed metal), every integrator
// agrees with the path tracer within the standard errors of both, region by region, at a low
// resolution; and the standard error of each falls as 1/√N with the sample count N.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <map>

#include "scene/scene_loader.h"
#include "integrators/integrator_factory.h"
#include "tests/integrator_names.h"
#include "integrators/render_loop.h"
#include "tests/region_batches.h"
#include "tests/support.h"

namespace kasha {
namespace {

constexpr int kRes = 24, kRegions = 2;  // 2×2 regions of a 24×24 image

struct Estimate {
  // mean and standard error per region and channel, over independent batches
  std::array<test::BatchStats, kRegions * kRegions * 3> stats;
};

std::unique_ptr<Scene> lowRes(const std::string& name) {
  auto scene = loadScene(test::sourcePath("scenes/" + name));
  test::useSquareCamera(*scene, kRes);
  return scene;
}

Estimate estimate(const Scene& scene, const std::string& integratorName, int spp, int batches) {
  RenderSettings settings = scene.render;
  settings.maxDepth = 8;
  const std::unique_ptr<Integrator> integrator = test::makeTestIntegrator(integratorName, scene, settings);
  const std::vector<test::BatchStats> v = test::regionBatches(
      scene, *integrator, kRes, kRes, kRegions * kRegions,
      [](int x, int y) { return (y * kRegions / kRes) * kRegions + x * kRegions / kRes; }, spp, batches, 7919);
  Estimate e;
  std::copy(v.begin(), v.end(), e.stats.begin());
  return e;
}

class Agreement : public ::testing::TestWithParam<std::tuple<const char*, const char*>> {};

TEST_P(Agreement, WithPathTracerRegionByRegion) {
  const auto [sceneName, integratorName] = GetParam();
  auto scene = lowRes(sceneName);
  // The UV scene is hard for every estimator (a small UV source seen through fluorescence):
  // more samples there, and most for the path tracer, whose fireflies dominate.
  const bool uv = std::string(sceneName) == "cornell_uv.json";
  static std::map<std::string, Estimate> references;  // one path-traced reference per scene
  if (!references.count(sceneName)) references[sceneName] = estimate(*scene, "pt", uv ? 1024 : 64, 12);
  const Estimate& ref = references[sceneName];
  const Estimate other = estimate(*scene, integratorName, uv ? 384 : 64, 12);
  // 12 comparisons per pair: 4.5σ keeps the chance of a false alarm below 1e-4.
  for (size_t i = 0; i < ref.stats.size(); ++i) {
    const double sigma = std::hypot(ref.stats[i].stderr_, other.stats[i].stderr_);
    EXPECT_LT(sigma, 0.1 * std::abs(ref.stats[i].mean) + 2e-3) << "too noisy to compare, region/channel " << i;
    EXPECT_NEAR(other.stats[i].mean, ref.stats[i].mean, 4.5 * sigma) << "region/channel " << i;
  }
}

class Convergence : public ::testing::TestWithParam<const char*> {};

TEST_P(Convergence, StandardErrorFallsAsOneOverRootN) {
  const std::string integratorName = GetParam();
  auto scene = lowRes("cornell_fluorescent.json");
  const Estimate a = estimate(*scene, integratorName, 16, 16), b = estimate(*scene, integratorName, 64, 16);
  // Quadrupling the samples halves the standard error; with 16 batches the ratio of two
  // estimated standard errors scatters by about ±25% (χ² with 15 degrees of freedom).
  double ratio = 0.0;
  for (size_t i = 0; i < a.stats.size(); ++i) ratio += b.stats[i].stderr_ / a.stats[i].stderr_ / double(a.stats.size());
  EXPECT_NEAR(ratio, 0.5, 0.15);
}

INSTANTIATE_TEST_SUITE_P(Cornell, Agreement,
                         ::testing::Combine(::testing::Values("cornell_fluorescent.json", "cornell_uv.json",
                                                              "cornell_glossy.json"),
                                            ::testing::Values("lt", "bdpt", "bdpt.both", "bdpt-shared", "bdpt-independent")));
INSTANTIATE_TEST_SUITE_P(Cornell, Convergence, ::testing::Values("pt", "lt", "bdpt", "bdpt-shared", "bdpt-independent"));

}  // namespace
}  // namespace kasha
