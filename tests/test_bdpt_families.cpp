// The unified bdpt's choice of light-subpath families (docs/bdpt-mis.md §13): the pilot's estimates
// against known variances, what a contribution tells it, its decision on scenes whose light needs
// the own family or not, and that the shared family alone is exactly bdpt-shared's estimator.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "integrators/bdpt/bdpt_integrator.h"
#include "integrators/bdpt/connect.h"
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
  // Half of the noise at the sample's own pixel, half splatted onto it; a known excess.
  const bdpt::PilotEstimates e = bdpt::pilotEstimates(
      w, h, 5, SamplerKind::Independent, [](Vec2 pixel, Sampler& rng, SampleContext& ctx, std::vector<Splat>& excess) {
        ctx.splats.push_back({pixel + Vec2(0.5f), 0.5f * noisy(rng)});
        excess.push_back({pixel, Vec3(0.5f)});  // the alternative's second moment over this one's: 0.5 per channel
        return 0.5f * noisy(rng);
      });
  // Two independent halves: Var = 2·(1/4)·(1/3) per channel around a mean of 1.
  EXPECT_NEAR(e.relVar, kNoisyRelVar / 2.0, 4.0 * noisyStandardError(w * h) / 2.0 + 0.01);
  EXPECT_NEAR(e.relExcess, 3.0 * 0.5 / 1.01, 0.02);  // the box mean: 1 up to the noise
}

TEST(FamilyPilot, SmallImagesTakeSeveralSamplesPerPixel) {
  constexpr int w = 16, h = 8;  // 128 pixels: 128 samples per pixel and image
  std::vector<int> samples(size_t(w * h), 0);
  const bdpt::PilotEstimates e = bdpt::pilotEstimates(
      w, h, 5, SamplerKind::Independent, [&](Vec2 pixel, Sampler& rng, SampleContext&, std::vector<Splat>&) {
        ++samples[size_t(pixel.y) * w + size_t(pixel.x)];  // each row is one task
        return noisy(rng);
      });
  for (int n : samples) EXPECT_EQ(n, 2 * 128);
  // Per sample, not per image mean: n·(x̄₁ − x̄₂)²/2 with x̄ near normal, so each pixel's estimate has a
  // standard deviation of √(3·2/9) over the three channels; the trimmed largest pixel lowers the mean.
  EXPECT_NEAR(e.relVar, kNoisyRelVar, 4.0 * std::sqrt(3.0 * 2.0 / 9.0 / (w * h)) + 0.05);
}

// What a contribution tells the pilot about the shared family alone (connect.h).
TEST(FamilyPilot, MomentsOfAContribution) {
  bdpt::PilotMoments m;
  m.ratio[0] = 3.0;                                    // p_both = 3 p_alone
  m.ratio[1] = 1.0;                                    // the same density
  m.ratio[2] = std::numeric_limits<double>::infinity();  // p_alone = 0
  m.add(0, Vec2(2.0f, 1.0f), Vec3(1.0f, 2.0f, 0.0f));
  m.add(1, Vec2(2.0f, 1.0f), Vec3(1.0f));
  m.add(2, Vec2(0.0f), Vec3(0.0f));  // no light: nothing
  ASSERT_EQ(m.excess.size(), 1u);
  EXPECT_EQ(m.excess[0].xyz.x, 2.0f);  // C²·(ρ − 1)
  EXPECT_EQ(m.excess[0].xyz.y, 8.0f);
  EXPECT_EQ(m.excess[0].xyz.z, 0.0f);
  EXPECT_EQ(m.unshared, 0);
  m.add(2, Vec2(0.0f), Vec3(0.0f, 1e-3f, 0.0f));
  EXPECT_EQ(m.unshared, 1);
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
// the lens hit so rarely that samples of the shared family alone hardly show it; both families'
// paths do. In the Cornell box lit by a visible lamp, the fluorescent wall's
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
  EXPECT_NE(st.choices.find("which cannot sample some paths that carry light"), std::string::npos) << st.choices;
  // Fixed families decide nothing; the shared family alone says so.
  RenderSettings settings = scene->render;
  settings.bdptFamilies = BdptFamilies::Both;
  EXPECT_EQ(makeIntegrator("bdpt", *scene, settings)->choices(), "");
  settings.bdptFamilies = BdptFamilies::Shared;
  EXPECT_EQ(makeIntegrator("bdpt", *scene, settings)->choices(), "families: shared");
}

}  // namespace
}  // namespace kasha
