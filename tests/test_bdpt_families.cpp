// The unified bdpt's choice of light-subpath families (docs/bdpt-mis.md §13): the pilot's variance
// estimates against known variances, its check that the two estimators agree, its decision on two
// scenes whose light needs the own family or not, and that the shared family alone is exactly
// bdpt-shared's estimator.
#include <gtest/gtest.h>

#include <cmath>

#include "integrators/bdpt/bdpt_integrator.h"
#include "integrators/bdpt/family_pilot.h"
#include "integrators/integrator_factory.h"
#include "integrators/render_loop.h"
#include "scene/scene_loader.h"
#include "tests/support.h"

namespace kasha {
namespace {

Vec3 noisy(Sampler& rng) { return Vec3(1.0f) + 2.0f * rng.uniform3() - Vec3(1.0f); }  // 1 + U(−1, 1) per channel

// Per channel, Var = 1/3 around a mean of 1: Σ_XYZ (1/3)/(1 + 10⁻²).
constexpr double kNoisyRelVar = 1.0 / 1.01;
// The standard error of the pilot's mean over n pixels of Σ_XYZ (x₁ − x₂)²/2, x = 1 + U(−1, 1):
// Var[(x₁ − x₂)²/2] = (E[d⁴] − E[d²]²)/4 = (16/15 − 4/9)/4 per channel.
double noisyStandardError(int pixels) { return std::sqrt(3.0 * (16.0 / 15.0 - 4.0 / 9.0) / 4.0 / pixels); }

TEST(FamilyPilot, MeasuresKnownVariancesOfSamplesAndSplats) {
  constexpr int w = 64, h = 48;
  // a: nothing at its own pixel, its noise splatted onto it; b: a constant.
  const bdpt::PilotVariances v = bdpt::pilotVariances(
      w, h, 5, SamplerKind::Independent,
      [](Vec2 pixel, Sampler& rng, SampleContext& a, SampleContext&, std::vector<Splat>& excess) {
        a.splats.push_back({pixel + Vec2(0.5f), noisy(rng)});
        excess.push_back({pixel, Vec3(0.5f)});  // b's second moment over a's: 0.5 per channel and sample
        return std::pair<Vec3, Vec3>(Vec3(0.0f), Vec3(1.0f));
      });
  // The box mean of the four images is 1 up to a's noise (about 1/√300 per channel).
  EXPECT_NEAR(v.a, kNoisyRelVar, 4.0 * noisyStandardError(w * h) + 0.01);
  EXPECT_EQ(v.b, 0.0);
  EXPECT_NEAR(v.excess, 3.0 * 0.5 / 1.01, 0.02);  // the box mean: 1 up to a's noise
  EXPECT_TRUE(v.agree);
}

TEST(FamilyPilot, FindsTheEstimatorThatMissesLight) {
  constexpr int w = 32, h = 32;
  // b is unbiased for 1 + U but finds it once in 10⁵ samples: the pilot's 2048 rarely see it.
  auto run = [](double rarity) {
    return bdpt::pilotVariances(w, h, 3, SamplerKind::Independent,
                                [=](Vec2, Sampler& rng, SampleContext&, SampleContext&, std::vector<Splat>&) {
      const Vec3 a = noisy(rng);
      const Vec3 b = rng.uniform() < 1.0 / rarity ? noisy(rng) * float(rarity) : Vec3(0.0f);
      return std::pair<Vec3, Vec3>(a, b);
    });
  };
  const bdpt::PilotVariances rare = run(1e5), always = run(1.0);
  EXPECT_FALSE(rare.agree);
  EXPECT_LT(rare.b, 0.01);  // what the pilot sees of b's variance: almost nothing
  EXPECT_TRUE(always.agree);
  EXPECT_NEAR(always.a, kNoisyRelVar, 4.0 * noisyStandardError(w * h) + 0.02);
  EXPECT_NEAR(always.b, kNoisyRelVar, 4.0 * noisyStandardError(w * h) + 0.02);
}

std::unique_ptr<Scene> smallScene(const char* file, int res) {
  auto scene = loadScene(test::sourcePath(file));
  const Camera& c = scene->camera;
  scene->camera = Camera(c.position(), c.position() + c.forward(), c.up(), c.fovYDegrees(), res, res);
  return scene;
}

std::unique_ptr<Integrator> automatic(const Scene& scene) {
  RenderSettings settings = scene.render;
  settings.bdptFamilies = BdptFamilies::Auto;
  return makeIntegrator("bdpt", scene, settings);
}

bool keepsOwnFamily(const Scene& scene) {
  const std::unique_ptr<Integrator> in = automatic(scene);
  RayCounter rays;
  return dynamic_cast<const Bdpt&>(*in).keepsOwnFamily(scene, 1, rays);
}

// uv_caustic.json: a UV point lamp's light reaches a fluorescent floor only through glass (a
// caustic), so no camera path can find it and the shared family alone misses it.
// uv_caustic_mirror.json: the same through a lens from a small UV LED, which camera paths through
// the lens hit so rarely that the pilot's own samples of the shared family alone hardly show it;
// both families' paths do. In the Cornell box lit by a visible lamp, the fluorescent wall's
// re-emission is a small part that camera paths find well.
TEST(BdptFamilies, ThePilotKeepsTheOwnFamilyWhereTheLightNeedsIt) {
  EXPECT_TRUE(keepsOwnFamily(*smallScene("scenes/uv_caustic.json", 48)));
  EXPECT_TRUE(keepsOwnFamily(*smallScene("scenes/uv_caustic_mirror.json", 48)));
  EXPECT_FALSE(keepsOwnFamily(*smallScene("scenes/cornell_fluorescent.json", 48)));
}

TEST(BdptFamilies, TheSharedFamilyAloneIsBdptShared) {
  const auto scene = smallScene("scenes/cornell_uv.json", 16);
  RenderSettings settings = scene->render;
  settings.bdptFamilies = BdptFamilies::Shared;
  Film alone(16, 16), shared(16, 16);
  RenderOptions opt;
  opt.spp = 4;
  opt.seed = 9;
  render(*scene, *makeIntegrator("bdpt", *scene, settings), alone, opt);
  render(*scene, *makeIntegrator("bdpt-shared", *scene, settings), shared, opt);
  for (int y = 0; y < 16; ++y)
    for (int x = 0; x < 16; ++x) {
      const Vec3 a = alone.xyz(x, y), b = shared.xyz(x, y);
      EXPECT_EQ(a.x, b.x);
      EXPECT_EQ(a.y, b.y);
      EXPECT_EQ(a.z, b.z);
    }
}

TEST(BdptFamilies, TheChoiceIsReported) {
  const auto scene = smallScene("scenes/uv_caustic.json", 48);
  const std::unique_ptr<Integrator> in = automatic(*scene);
  Film film(48, 48);
  RenderOptions opt;
  opt.spp = 1;
  EXPECT_EQ(in->choices(), "");  // nothing decided before the render
  const RenderStats st = render(*scene, *in, film, opt);
  EXPECT_EQ(st.choices.rfind("families: both (pilot: ", 0), 0u) << st.choices;
  // The lamp's light reaches the floor only through glass: the shared family alone cannot sample it.
  EXPECT_NE(st.choices.find("shared alone cannot sample some paths that carry light"), std::string::npos) << st.choices;
  // Fixed families decide nothing; the shared family alone says so.
  RenderSettings settings = scene->render;
  settings.bdptFamilies = BdptFamilies::Both;
  EXPECT_EQ(makeIntegrator("bdpt", *scene, settings)->choices(), "");
  settings.bdptFamilies = BdptFamilies::Shared;
  EXPECT_EQ(makeIntegrator("bdpt", *scene, settings)->choices(), "families: shared");
}

}  // namespace
}  // namespace kasha
