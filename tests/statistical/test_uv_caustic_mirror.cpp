// The scene that needs both connections and merging (scenes/uv_caustic_mirror.json, issue 14): a
// 385 nm LED reaches the Pacific-Blue floor only through a ball lens. Looking at the caustic at low
// resolution, BDPT (connections) and photon mapping (merging) must agree region by region within 4
// combined standard errors (docs/validation.md §4), and the caustic must stand out of the floor around it.
#include <gtest/gtest.h>

#include <memory>
#include <vector>

#include "scene/scene_loader.h"
#include "integrators/integrator_factory.h"
#include "tests/integrator_names.h"
#include "tests/region_batches.h"
#include "tests/support.h"

namespace kasha {
namespace {

constexpr int kRes = 16, kRegions = 4;  // 4 × 4 regions of 4 × 4 pixels

// The scene's camera turned to the caustic under the lens (the lens centre is at x = 0, z = 0.35),
// 0.45 m of floor across and the glossy mirror out of sight: the caustic's ellipse fills the two
// middle rows of regions, bare floor the top and bottom rows.
std::unique_ptr<Scene> causticView() {
  auto scene = loadScene(test::sourcePath("scenes/uv_caustic_mirror.json"));
  test::aimCamera(*scene, Vec3(0.0f, 0.0f, 0.30f), 11.0f, kRes);
  test::setPhotons(*scene, 20000, 0.007f);  // a small radius: its blur would move light across the caustic's rim
  return scene;
}

int regionOf(int x, int y) { return (y * kRegions / kRes) * kRegions + x * kRegions / kRes; }

std::vector<test::BatchStats> regions(const Scene& scene, const char* integrator, int spp, int batches) {
  const std::unique_ptr<Integrator> it = test::makeTestIntegrator(integrator, scene, scene.render);
  return test::regionBatches(scene, *it, kRes, kRes, kRegions * kRegions, regionOf, spp, batches, 7919);
}

TEST(UvCausticMirrorSlow, ConnectionsAndMergingAgreeOnTheCaustic) {  // Slow: the sanitizer stage skips it
  const auto scene = causticView();
  const auto bdpt = regions(*scene, "bdpt", 32, 32);
  const auto ppm = regions(*scene, "ppm", 6, 32);
  test::expectRegionsAgree(bdpt, ppm, 4.0, 0.1, 0.02);
}

TEST(UvCausticMirror, TheCausticOutshinesTheFloorAroundIt) {
  const auto scene = causticView();
  const auto xyz = regions(*scene, "bdpt", 4, 4);
  // Mean Z (channel 2: Pacific Blue emits around 455 nm, under z̄) of the four central regions
  // against the eight of the top and bottom rows.
  double centre = 0.0, floor = 0.0;
  for (int r = 0; r < kRegions * kRegions; ++r) {
    const int row = r / kRegions, column = r % kRegions;
    if (row == 0 || row == kRegions - 1) floor += xyz[size_t(r * 3 + 2)].mean / 8.0;
    else if (column == 1 || column == 2) centre += xyz[size_t(r * 3 + 2)].mean / 4.0;
  }
  EXPECT_GT(centre, 5.0 * floor);
}

}  // namespace
}  // namespace kasha
