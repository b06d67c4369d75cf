// The Post-it scenes (docs/measured-materials.md): measured reradiation matrices and their Zhdanov
// fits under daylight and under a UV-A LED. Camera paths sample the measured matrix along its rows
// (Radiance mode) and light paths along its columns (Importance mode), so agreement between the
// path tracer, the light tracer and BDPT, quadrant by quadrant (one note each) within the
// standard errors, checks that the two modes describe one material.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <map>

#include "scene/scene_loader.h"
#include "integrators/integrator_factory.h"
#include "tests/region_batches.h"
#include "tests/support.h"

namespace kasha {
namespace {

constexpr int kW = 24, kH = 18;

using Estimate = std::array<test::BatchStats, 4 * 3>;  // quadrant × XYZ

Estimate estimate(const Scene& scene, const std::string& integratorName, int spp, int batches) {
  const std::unique_ptr<Integrator> integrator = makeIntegrator(integratorName, scene, scene.render);
  const std::vector<test::BatchStats> v = test::regionBatches(
      scene, *integrator, kW, kH, 4, [](int x, int y) { return (2 * y / kH) * 2 + 2 * x / kW; }, spp, batches, 104729);
  Estimate e;
  std::copy(v.begin(), v.end(), e.begin());
  return e;
}

class PostIt : public ::testing::TestWithParam<std::tuple<const char*, const char*>> {};

TEST_P(PostIt, IntegratorsAgreeWithTheLightTracerSlow) {
  const auto [sceneName, integratorName] = GetParam();
  auto scene = loadScene(test::sourcePath(std::string("scenes/") + sceneName));
  const Camera& c = scene->camera;
  scene->camera = Camera(c.position(), c.position() + c.forward(), Vec3(0, 1, 0), c.fovYDegrees(), kW, kH);
  static std::map<std::string, Estimate> references;
  if (!references.count(sceneName)) references[sceneName] = estimate(*scene, "lt", 256, 12);
  const Estimate& ref = references[sceneName];
  // Under UV, the path tracer finds the LED only through the excitation wavelengths it samples, and
  // BDPT with a shared wavelength starts its light subpaths at the camera's visible wavelength,
  // where the LED emits nothing, so it reduces to the same strategies: more samples for both.
  const bool uvPt = std::string(sceneName) == "postit_uv.json" && std::string(integratorName) != "bdpt-independent";
  const Estimate other = estimate(*scene, integratorName, uvPt ? 1024 : 128, 12);
  // Precise enough to mean something: 10% of the value, or 2% of the brightest one for dim notes.
  // 12 comparisons per pair: 4.5σ keeps the chance of a false alarm below 1e-4.
  test::expectRegionsAgree(ref, other, 4.5, 0.1, 0.02);
}

INSTANTIATE_TEST_SUITE_P(Scenes, PostIt,
                         ::testing::Combine(::testing::Values("postit_d65.json", "postit_uv.json"),
                                            ::testing::Values("pt", "bdpt-shared", "bdpt-independent")));

}  // namespace
}  // namespace kasha
