// The Mitsuba-format Cornell box (scenes/mitsuba/cornell_box.xml: OBJ walls scaled by a
// transform, spheres and light placed by transforms, kasha's jung_fluorescent extension) renders
// the same image as the native scenes/cornell_fluorescent.json: the X, Y, Z sums of 4 × 4 image
// regions agree within 4 standard errors of independent batch renders (different seeds for the
// two scenes). A negative control shows the comparison can fail: making the FITC sphere plain in
// the native scene is detected.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include "scene/scene_loader.h"
#include "integrators/integrator_factory.h"
#include "tests/region_batches.h"
#include "tests/support.h"

namespace kasha {
namespace {

// Many small batches: the standard errors are then estimated with ~60 degrees of freedom, so a
// 4σ bound over 48 comparisons is a sharp test, not a t-distribution lottery.
constexpr int kRes = 32, kGrid = 4, kSpp = 4, kBatches = 32;

std::vector<test::BatchStats> regions(Scene& scene, uint64_t seedStep) {
  const Camera& c = scene.camera;
  scene.camera = Camera(c.position(), c.position() + c.forward(), c.up(), c.fovYDegrees(), kRes, kRes);
  const std::unique_ptr<Integrator> pt = makeIntegrator("pt", scene, scene.render);
  return test::regionBatches(scene, *pt, kRes, kRes, kGrid * kGrid,
                             [](int x, int y) { return (y * kGrid / kRes) * kGrid + x * kGrid / kRes; }, kSpp, kBatches,
                             seedStep);
}

// Largest |difference| / combined standard error over regions and channels.
double worstSigma(const std::vector<test::BatchStats>& a, const std::vector<test::BatchStats>& b) {
  double worst = 0.0;
  for (size_t i = 0; i < a.size(); ++i) {
    const double se = std::hypot(a[i].stderr_, b[i].stderr_);
    worst = std::max(worst, std::abs(a[i].mean - b[i].mean) / se);
  }
  return worst;
}

TEST(MitsubaCornell, RendersLikeTheNativeScene) {
  const auto xml = loadScene(test::sourcePath("scenes/mitsuba/cornell_box.xml"));
  const auto native = loadScene(test::sourcePath("scenes/cornell_fluorescent.json"));
  ASSERT_EQ(xml->render.maxDepth, native->render.maxDepth);
  const auto a = regions(*xml, 1000), b = regions(*native, 7);
  const double worst = worstSigma(a, b);
  RecordProperty("worst_sigma", std::to_string(worst));
  EXPECT_LT(worst, 4.0);
}

TEST(MitsubaCornell, ComparisonDetectsAPlainSphere) {
  const auto xml = loadScene(test::sourcePath("scenes/mitsuba/cornell_box.xml"));
  std::ifstream in(test::sourcePath("scenes/cornell_fluorescent.json"));
  nlohmann::json j = nlohmann::json::parse(in);
  j["shapes"][6]["material"] = "plain_green";  // the FITC sphere loses its fluorescence
  const auto plain = loadSceneFromJson(j, test::sourcePath("scenes/cornell_fluorescent.json"));
  const double worst = worstSigma(regions(*xml, 1000), regions(*plain, 7));
  RecordProperty("worst_sigma", std::to_string(worst));
  EXPECT_GT(worst, 4.0);
}

}  // namespace
}  // namespace kasha
