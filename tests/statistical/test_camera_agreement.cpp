// docs/validation.md §4, the cameras: through a thin lens focused in front of a diffuse plane, and
// through an orthographic camera, light tracing (every path through the camera connection, t = 1)
// and BDPT agree with the path tracer (camera rays alone) region by region within 4 standard
// errors. The scene (scenes/validation/defocus_plane.json) has an edge between a bright and a dark
// half and a light to the side, so that the defocus and the projection change the image.
#include <gtest/gtest.h>

#include <map>

#include "scene/scene_loader.h"
#include "tests/integrator_names.h"
#include "tests/region_batches.h"

namespace kasha {
namespace {

constexpr int kRes = 8, kRegions = 4;  // 4×4 regions of 2×2 pixels

std::unique_ptr<Scene> withCamera(const std::string& camera) {
  auto scene = loadScene(test::sourcePath("scenes/validation/defocus_plane.json"));
  if (camera == "orthographic") {
    const Camera& c = scene->camera;
    scene->camera = Camera::orthographic(c.position(), c.position() + c.forward(), c.up(), Vec2(3.0f), kRes, kRes);
  }
  EXPECT_EQ(scene->camera.width(), kRes);
  return scene;
}

std::vector<test::BatchStats> estimate(const Scene& scene, const std::string& integratorName, int spp) {
  RenderSettings settings = scene.render;
  const std::unique_ptr<Integrator> integrator = test::makeTestIntegrator(integratorName, scene, settings);
  return test::regionBatches(
      scene, *integrator, kRes, kRes, kRegions * kRegions,
      [](int x, int y) { return (y * kRegions / kRes) * kRegions + x * kRegions / kRes; }, spp, 32, 3571);
}

class CameraAgreement : public ::testing::TestWithParam<std::tuple<const char*, const char*>> {};

TEST_P(CameraAgreement, WithPathTracerRegionByRegion) {
  const auto [camera, integratorName] = GetParam();
  const auto scene = withCamera(camera);
  static std::map<std::string, std::vector<test::BatchStats>> references;  // pt, one per camera
  if (!references.count(camera)) references[camera] = estimate(*scene, "pt", 256);
  // Light tracing reaches the film through the connection alone: more samples for the same error.
  const std::vector<test::BatchStats> other = estimate(*scene, integratorName, std::string(integratorName) == "lt" ? 1024 : 256);
  test::expectRegionsAgree(references[camera], other, 4.0, 0.1, 0.02);
}

INSTANTIATE_TEST_SUITE_P(Cameras, CameraAgreement,
                         ::testing::Combine(::testing::Values("thinlens", "orthographic"), ::testing::Values("lt", "bdpt")),
                         [](const auto& info) {
                           return std::string(std::get<0>(info.param)) + "_" + std::get<1>(info.param);
                         });

}  // namespace
}  // namespace kasha
