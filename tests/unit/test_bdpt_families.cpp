// The unified bdpt's choice of light-subpath families (docs/bdpt-mis.md §13): the pilot's estimates
// against known variances, what a contribution tells it, its decision on scenes whose light needs
// the own family or not, and that the family the pilot runs alone is exactly that family's fixed
// estimator (render/bdpt/families).
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "integrators/bidirectional/bdpt.h"
#include "integrators/bidirectional/family_pilot.h"
#include "integrators/bidirectional/pilot_observer.h"
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

// Half of the noise at the sample's own pixel, half splatted onto it; known excesses of two
// alternatives. 64 × 48 pixels are sampled one by one; 256 × 256 in cells of 4 × 2 pixels, whose
// splats add up in the cell: the estimates are the same.
void measuresKnownVariances(int w, int h) {
  const bidir::PilotEstimates e = bidir::pilotEstimates(
      w, h, 5, SamplerKind::Independent, 2,
      [](Vec2 pixel, Sampler& rng, SampleContext& ctx, std::vector<std::vector<Splat>>& excess) {
        ctx.splats.push_back({pixel + Vec2(0.5f), 0.5f * noisy(rng)});
        // The alternatives' second moments over this one's: 0.5 and −0.25 per channel.
        excess[0].push_back({pixel, Vec3(0.5f)});
        excess[1].push_back({pixel + Vec2(0.5f), Vec3(-0.25f)});
        return 0.5f * noisy(rng);
      });
  const int cells = std::min(w * h, 8192), n = (8192 + cells - 1) / cells;  // n samples per cell and image
  EXPECT_EQ(e.samples, size_t(2 * n * cells));
  // Two independent halves: Var = 2·(1/4)·(1/3) per channel around a mean of 1.
  EXPECT_NEAR(e.relVar, kNoisyRelVar / 2.0, 4.0 * noisyStandardError(cells) / 2.0 + 0.01);
  ASSERT_EQ(e.relExcess.size(), 2u);
  // Divided by the neighbours' mean m² (+ 10⁻²): m is 1 up to its noise, the mean of 2·24 cell values
  // of variance (1/6)/n, so E[1/m²] ≈ 1 + 3·Var m.
  const double inverseSquare = 1.0 + 3.0 * (1.0 / 6.0) / (48.0 * n);
  EXPECT_NEAR(e.relExcess[0], 3.0 * 0.5 / 1.01 * inverseSquare, 0.01);
  EXPECT_NEAR(e.relExcess[1], -3.0 * 0.25 / 1.01 * inverseSquare, 0.005);
}

TEST(FamilyPilot, MeasuresKnownVariancesOfSamplesAndSplats) { measuresKnownVariances(64, 48); }
TEST(FamilyPilot, LargeImagesAreSampledInCells) { measuresKnownVariances(256, 256); }

// An estimator whose variance is rare large samples: 1 + X with probability p, else 1 (per channel).
// Its relative variance per sample is X²·p(1 − p)·E[1/(m² + 10⁻²)] per channel, m the stand-in for
// the reference: the mean of the 48 other samples of the cell's 5×5 neighbourhood, 1 + X·k/48 with k of
// them large (binomial), independent of the cell's own two samples. Were the cell in its own mean, a
// large sample would divide itself by about (X/50)², and the estimate was ×400 lower.
TEST(FamilyPilot, RareLargeSamplesAreNotHiddenByTheirOwnCellsMean) {
  constexpr int w = 128, h = 64;  // 8192 cells of one pixel, one sample each per image
  constexpr double X = 1000.0, p = 0.005;
  const bidir::PilotEstimates e = bidir::pilotEstimates(
      w, h, 11, SamplerKind::Independent, 0, [&](Vec2, Sampler& rng, SampleContext&, std::vector<std::vector<Splat>>&) {
        return Vec3(1.0f + (rng.uniform() < p ? float(X) : 0.0f));
      });
  double inverse = 0.0, binomial = std::pow(1.0 - p, 48.0);  // P(k = 0)
  for (int k = 0; k <= 48; ++k) {
    const double m = 1.0 + X * k / 48.0;
    inverse += binomial / (m * m + 1e-2);
    binomial *= (48.0 - k) / (k + 1.0) * p / (1.0 - p);
  }
  const double expected = 3.0 * X * X * p * (1.0 - p) * inverse;
  // The estimate is a sum over the cells whose two samples differ, about λ = 8192·2p(1 − p) = 81 of
  // them, each divided by its own m²: its relative standard error is √(E[Y²]/λ)/E[Y] with Y = 1/(m²
  // + 10⁻²), 12.5% here (the border cells' fewer neighbours and the trimmed largest cell move it by
  // about 2%).
  const double cells = w * h * 2.0 * p * (1.0 - p);
  double second = 0.0;
  binomial = std::pow(1.0 - p, 48.0);
  for (int k = 0; k <= 48; ++k) {
    const double m = 1.0 + X * k / 48.0;
    second += binomial / ((m * m + 1e-2) * (m * m + 1e-2));
    binomial *= (48.0 - k) / (k + 1.0) * p / (1.0 - p);
  }
  EXPECT_NEAR(e.relVar, expected, 4.0 * expected * std::sqrt(second / cells) / inverse);
}

TEST(FamilyPilot, SmallImagesTakeSeveralSamplesPerPixel) {
  constexpr int w = 16, h = 8;  // 128 pixels: 64 samples per pixel and image
  std::vector<int> samples(size_t(w * h), 0);
  const bidir::PilotEstimates e = bidir::pilotEstimates(
      w, h, 5, SamplerKind::Independent, 0,
      [&](Vec2 pixel, Sampler& rng, SampleContext&, std::vector<std::vector<Splat>>&) {
        ++samples[size_t(pixel.y) * w + size_t(pixel.x)];  // each row is one task
        return noisy(rng);
      });
  for (int n : samples) EXPECT_EQ(n, 2 * 64);
  // Per sample, not per image mean: n·(x̄₁ − x̄₂)²/2 with x̄ near normal, so each pixel's estimate has a
  // standard deviation of √(3·2/9) over the three channels; the trimmed largest pixel lowers the mean.
  EXPECT_NEAR(e.relVar, kNoisyRelVar, 4.0 * std::sqrt(3.0 * 2.0 / 9.0 / (w * h)) + 0.05);
}

TEST(FamilyPilot, RaysOfSamplesAreCountedOnce) {
  std::vector<int> pixels(size_t(40 * 30), 0);
  const RayCounter r = bidir::raysOfSamples(
      40, 30, 5, SamplerKind::Independent, 600,
      [&](Vec2 pixel, Sampler&, SampleContext& ctx, std::vector<std::vector<Splat>>&) {
        ++pixels[size_t(pixel.y) * 40 + size_t(pixel.x)];  // a task each
        ctx.counter.closest += 3, ctx.counter.shadow += 1;
        return Vec3(0.0f);
      });
  EXPECT_EQ(r.closest, 3u * 600u);
  EXPECT_EQ(r.shadow, 600u);
  // Each at a pixel of its own, spread over rows and columns (bidir::spreadPixels: a 28 × 22 grid).
  int rows = 0, columns = 0, visited = 0;
  for (int y = 0; y < 30; ++y) {
    int n = 0;
    for (int x = 0; x < 40; ++x) n += pixels[size_t(y) * 40 + size_t(x)];
    rows += n > 0;
  }
  for (int x = 0; x < 40; ++x) {
    int n = 0;
    for (int y = 0; y < 30; ++y) n += pixels[size_t(y) * 40 + size_t(x)];
    columns += n > 0;
  }
  for (int v : pixels) {
    EXPECT_LE(v, 1);
    visited += v;
  }
  EXPECT_EQ(visited, 600);
  EXPECT_EQ(rows, 22);
  EXPECT_EQ(columns, 28);
}

// What a contribution tells the pilot about each family alone (pilot_observer.h).
TEST(FamilyPilot, MomentsOfAContribution) {
  bidir::PilotMoments m;
  auto& shared = m.alone[int(bidir::Alone::Shared)];
  auto& own = m.alone[int(bidir::Alone::Own)];
  shared.ratio[0] = 3.0, own.ratio[0] = 0.5;  // p_both = 3 p_shared-alone, p_both = p_own-alone / 2
  shared.ratio[1] = own.ratio[1] = 1.0;       // the same density
  shared.ratio[2] = std::numeric_limits<double>::infinity(), own.ratio[2] = 1.0;  // p_shared-alone = 0
  m.add(0, Vec2(2.0f, 1.0f), Vec3(1.0f, 2.0f, 0.0f));
  m.add(1, Vec2(2.0f, 1.0f), Vec3(1.0f));
  m.add(2, Vec2(0.0f), Vec3(0.0f));  // no light: nothing
  ASSERT_EQ(shared.excess.size(), 1u);
  EXPECT_EQ(shared.excess[0].xyz, Vec3(2.0f, 8.0f, 0.0f));  // C²·(ρ − 1)
  ASSERT_EQ(own.excess.size(), 1u);
  EXPECT_EQ(own.excess[0].xyz, Vec3(-0.5f, -2.0f, 0.0f));  // lower: the own family alone does better
  EXPECT_EQ(shared.unsampled, 0);
  m.add(2, Vec2(0.0f), Vec3(0.0f, 1e-3f, 0.0f));
  EXPECT_EQ(shared.unsampled, 1);
  EXPECT_EQ(own.unsampled, 0);
  m.clear();
  EXPECT_TRUE(shared.excess.empty() && own.excess.empty() && shared.unsampled == 0);
}

std::unique_ptr<Scene> smallScene(const char* file, int res) {
  auto scene = loadScene(test::sourcePath(file));
  const Camera& c = scene->camera;
  scene->camera = Camera(c.position(), c.position() + c.forward(), c.up(), c.fovYDegrees(), res, res);
  return scene;
}

std::unique_ptr<Integrator> automatic(const Scene& scene) {
  RenderSettings settings = scene.render;
  settings.bdpt.families = BdptFamilies::Auto;
  return makeIntegrator("bdpt", scene, settings);
}

BdptFamilies pilotChoice(const Scene& scene) {
  const std::unique_ptr<Integrator> in = automatic(scene);
  RayCounter rays;
  return dynamic_cast<const Bdpt&>(*in).pilotChoice(scene, 1, rays);
}

// uv_caustic.json: a UV point lamp's light reaches a fluorescent floor only through glass (a
// caustic), so no camera path can find it and the shared family alone misses it; the own family's
// light subpaths carry nearly all of it, so the shared family adds nothing and costs next to nothing.
// uv_caustic_mirror.json: the same through a lens from a small UV LED, which camera paths through
// the lens hit so rarely that samples of the shared family alone hardly show it; the own family's
// light subpaths find it, and the shared family's joins gain less than their rays cost.
// In the Cornell box lit by a visible lamp, the fluorescent wall's re-emission is a small part that
// camera paths find well, and the shared family's joins carry the diffuse light best.
TEST(BdptFamilies, ThePilotChoosesFamiliesThatSampleTheLight) {
  const BdptFamilies caustic = pilotChoice(*smallScene("scenes/uv_caustic.json", 48));
  EXPECT_TRUE(caustic == BdptFamilies::Both || caustic == BdptFamilies::Own) << toString(caustic);
  EXPECT_EQ(pilotChoice(*smallScene("scenes/uv_caustic_mirror.json", 48)), BdptFamilies::Own);
  EXPECT_EQ(pilotChoice(*smallScene("scenes/cornell_fluorescent.json", 48)), BdptFamilies::Shared);
}

// The family the pilot chose, run alone by the unified estimator (both families' light subpath
// start, the pilot's pass), is exactly the estimator of that family fixed (its own wavelength mode):
// the same image from the same seed.
void pilotsChoiceIsTheFixedFamily(const char* file, BdptFamilies expected) {
  constexpr int kRes = 48;
  const auto scene = smallScene(file, kRes);
  RenderSettings settings = scene->render;
  settings.bdpt.families = expected;
  Film chosen(kRes, kRes), fixed(kRes, kRes);
  RenderOptions opt;
  opt.spp = 2;
  opt.seed = 9;
  const RenderStats st = render(*scene, *automatic(*scene), chosen, opt);
  ASSERT_EQ(st.choices.rfind(std::string("families: ") + toString(expected) + " (pilot", 0), 0u) << st.choices;
  render(*scene, *makeIntegrator("bdpt", *scene, settings), fixed, opt);
  for (int y = 0; y < kRes; ++y)
    for (int x = 0; x < kRes; ++x) {
      const Vec3 a = chosen.xyz(x, y), b = fixed.xyz(x, y);
      EXPECT_EQ(a.x, b.x);
      EXPECT_EQ(a.y, b.y);
      EXPECT_EQ(a.z, b.z);
    }
}

TEST(BdptFamilies, TheSharedFamilyChosenIsTheFixedSharedFamily) {
  pilotsChoiceIsTheFixedFamily("scenes/cornell_fluorescent.json", BdptFamilies::Shared);
}
TEST(BdptFamilies, TheOwnFamilyChosenIsTheFixedOwnFamily) {
  pilotsChoiceIsTheFixedFamily("scenes/uv_caustic_mirror.json", BdptFamilies::Own);
}

TEST(BdptFamilies, TheChoiceIsReported) {
  const auto scene = smallScene("scenes/uv_caustic.json", 48);
  const std::unique_ptr<Integrator> in = automatic(*scene);
  Film film(48, 48);
  RenderOptions opt;
  opt.spp = 1;
  EXPECT_EQ(in->choices(), "");  // nothing decided before the render
  const RenderStats st = render(*scene, *in, film, opt);
  EXPECT_EQ(st.choices.rfind("families: ", 0), 0u) << st.choices;
  EXPECT_NE(st.choices.find(" (pilot: relative variance per sample and rays per sample: both "), std::string::npos)
      << st.choices;
  // The lamp's light reaches the floor only through glass: the shared family alone cannot sample it.
  EXPECT_NE(st.choices.find("shared alone cannot sample some paths that carry light"), std::string::npos) << st.choices;
  // Fixed families decide nothing; the shared family alone says so.
  RenderSettings settings = scene->render;
  settings.bdpt.families = BdptFamilies::Both;
  EXPECT_EQ(makeIntegrator("bdpt", *scene, settings)->choices(), "");
  settings.bdpt.families = BdptFamilies::Shared;
  EXPECT_EQ(makeIntegrator("bdpt", *scene, settings)->choices(), "families: shared");
  settings.bdpt.families = BdptFamilies::Own;
  EXPECT_EQ(makeIntegrator("bdpt", *scene, settings)->choices(), "families: own");
}

}  // namespace
}  // namespace kasha
