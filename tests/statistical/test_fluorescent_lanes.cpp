// Wavelength lanes ended at fluorescent events (--set fluorescent_lanes=end, the experiment that
// compares kasha's lanes through fluorescence with what ART, Mojzík et al. and pbrt-style renderers
// do; docs/wavelength-sampling.md "Lanes through fluorescent events"):
// - the lane event itself: one new lane per lane before, each serving that lane alone, and
//   lanesEndAt asks for one to be kept; through, a fresh set serves every lane;
// - unbiased: pt (the material's own excitation density and a strategy's) and lt match the closed
//   forms of docs/validation.md §1 (disjoint and overlapping a/e, UV only) within 4 standard errors;
// - the lanes really end: in the UV furnace, where every visible wavelength comes from a fluorescent
//   event, the variance per sample is larger with `end` than with `through` (and the mean the same).
#include <gtest/gtest.h>

#include "integrators/wavelength_lanes.h"
#include "scene/wavelength_strategy.h"
#include "tests/closed_form_support.h"

namespace kasha {
namespace {

using namespace test;

const Material& wall(const Scene& scene) { return *scene.materials.at(size_t(scene.shapes.at(0).material)); }

Bsdf bsdfAt(const Material& m, std::span<const float> lanes) {
  const Frame world{Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)};
  return m.bsdf(HitContext{Vec2(0.0f), world, world, lanes});
}

TEST(FluorescentLanes, EndGivesOneLanePerLaneBeforeAndKeepsOne) {
  // furnace_overlap.json: every lane below can fluoresce (its emission band covers them).
  const auto scene = load("furnace_overlap.json");
  const float known[4] = {480.0f, 500.0f, 520.0f, 540.0f};
  const Bsdf bsdf = bsdfAt(wall(*scene), known);
  for (const TransportMode mode : {TransportMode::Radiance, TransportMode::Importance}) {
    // u = 0 takes the fluorescent lobe (its probability is positive at every lane).
    const LaneEvent through = sampleLaneEvent(bsdf, mode, known, 4, 0.0f);
    ASSERT_EQ(through.lobe, SpectralLobe::Fluorescent);
    EXPECT_EQ(through.n, 4);
    EXPECT_FALSE(lanesEndAt(through, bsdf));
    for (int k = 0; k < through.n; ++k) EXPECT_EQ(through.source[k], kEveryLane);

    LaneEvent ended = sampleLaneEvent(bsdf, mode, known, 4, 0.0f, nullptr, FluorescentLanes::End);
    ASSERT_EQ(ended.lobe, SpectralLobe::Fluorescent);
    ASSERT_EQ(ended.n, 4);
    EXPECT_TRUE(lanesEndAt(ended, bsdf));
    // Lane k is kept with odds P(λ_k), the fluorescent-lobe probability of the lane before.
    float p[4], total = 0.0f;
    for (int k = 0; k < ended.n; ++k) {
      EXPECT_EQ(ended.source[k], k);
      EXPECT_GT(ended.scale[k], 0.0f);
      p[k] = bsdf.fluorescenceProbability(mode, known[k]);
      EXPECT_EQ(ended.odds[k], p[k]);
      total += p[k];
    }
    // u just past the first two lanes' share keeps lane 2: its own wavelength, its weight over
    // its probability.
    const LaneEvent before = ended;
    keepOneLane(ended, (p[0] + p[1]) / total + 1e-4f);
    EXPECT_EQ(ended.n, 1);
    EXPECT_EQ(ended.source[0], 2);
    EXPECT_EQ(ended.lambda[0], before.lambda[2]);
    EXPECT_FLOAT_EQ(ended.scale[0], before.scale[2] * total / p[2]);
  }
}

TEST(FluorescentLanes, KeepOneLaneKeepsEachWithItsOddsAndIsUnbiased) {
  // Lanes of scales 1, 2, 3, 4 with odds 0, 1, 1, 2: over a fine grid of u, lane j is kept with
  // probability odds/4, and the mean of the kept scale is the sum of the scales that can be kept.
  const int grid = 4000;
  double mean = 0.0;
  int kept[4] = {};
  for (int i = 0; i < grid; ++i) {
    LaneEvent e;
    e.n = 4;
    for (int j = 0; j < 4; ++j) e.lambda[j] = 500.0f + float(j), e.source[j] = j, e.scale[j] = float(j + 1);
    e.odds[0] = 0.0f, e.odds[1] = 1.0f, e.odds[2] = 1.0f, e.odds[3] = 2.0f;
    keepOneLane(e, (float(i) + 0.5f) / float(grid));
    ASSERT_EQ(e.n, 1);
    ++kept[e.source[0]];
    mean += e.scale[0] / grid;
  }
  EXPECT_EQ(kept[0], 0);
  EXPECT_EQ(kept[1], grid / 4);
  EXPECT_EQ(kept[2], grid / 4);
  EXPECT_EQ(kept[3], grid / 2);
  EXPECT_NEAR(mean, 2.0 + 3.0 + 4.0, 1e-4);
}

struct EndCase {
  const char* integrator;
  int lanes;
  const char* sensor = "cmf";
  const char* fluorescence = "material";
  int sppScale = 1;  // light tracing: most paths miss the small camera
};

void PrintTo(const EndCase& c, std::ostream* os) {
  *os << c.integrator << " lanes=" << c.lanes << " sensor=" << c.sensor << " fluorescence=" << c.fluorescence;
}

class EndedLanes : public ::testing::TestWithParam<EndCase> {};

TEST_P(EndedLanes, MatchFurnaceClosedForms) {
  const EndCase& ec = GetParam();
  for (const char* name : {"furnace_fluorescent.json", "furnace_overlap.json", "furnace_uv.json"}) {
    SCOPED_TRACE(name);
    auto scene = load(name);
    RenderSettings settings = scene->render;
    settings.maxDepth = 1000;
    settings.rrDepth = 3;
    settings.heroWavelengths = ec.lanes;
    settings.wavelengths.sensor = parseWavelengthSpec(ec.sensor);
    settings.wavelengths.fluorescence = parseWavelengthSpec(ec.fluorescence);
    settings.fluorescentLanes = FluorescentLanes::End;
    const Grid g(scene->range);
    expectXyzAgreement(*scene, ec.integrator, settings, toXyz(g, furnaceClosedForm(g, jung(*scene), emissionOf(*scene))),
                       16, 128 * ec.sppScale);
  }
}

INSTANTIATE_TEST_SUITE_P(Integrators, EndedLanes,
                         ::testing::Values(EndCase{"pt", 4}, EndCase{"pt", 3, "mix:cmf,light", "mix:absorption,uniform", 2},
                                           EndCase{"lt", 4, "cmf", "material", 8}),
                         [](const auto& info) {
                           return std::string(info.param.integrator) + "_" + std::to_string(info.param.lanes) +
                                  (std::string(info.param.fluorescence) == "material" ? "" : "_strategy");
                         });

// The mean and the variance of the mean Y of `batches` renders.
std::pair<double, double> meanAndVariance(const Scene& scene, const Integrator& integrator, int batches, int spp) {
  std::vector<double> y;
  for (const DVec3& m : batchMeans(scene, integrator, batches, spp, 2000)) y.push_back(m.y);
  const BatchStats s = batchStats(y);
  return {s.mean, s.stderr_ * s.stderr_ * double(batches)};
}

struct VarianceCase {
  const char* integrator;
  int spp;
  double minRatio;  // the variance with `end` must exceed the one with `through` by this factor
};

class LanesEnd : public ::testing::TestWithParam<VarianceCase> {};

TEST_P(LanesEnd, KeepTheMeanAndRaiseTheVariance) {
  // The UV furnace: all visible light is re-emitted, and after a fluorescent event the lanes go on
  // as one with `end`. Measured variance ratios end/through (1024 batches): pt 13, lt 1.8; if the
  // lanes did not end (all of them going on, each serving its own lane before) pt 4.7, lt 1.0; if
  // the option did nothing, 1.
  auto scene = load("furnace_uv.json");
  RenderSettings settings = scene->render;
  settings.heroWavelengths = 4;
  const VarianceCase& vc = GetParam();
  const int batches = 1024;
  const auto through = meanAndVariance(*scene, *makeIntegrator(vc.integrator, *scene, settings), batches, vc.spp);
  settings.fluorescentLanes = FluorescentLanes::End;
  const auto ended = meanAndVariance(*scene, *makeIntegrator(vc.integrator, *scene, settings), batches, vc.spp);
  const double stderrOfDifference = std::sqrt((through.second + ended.second) / batches);
  EXPECT_NEAR(through.first, ended.first, 4.0 * stderrOfDifference);
  EXPECT_GT(ended.second, vc.minRatio * through.second) << "variance through " << through.second << ", ended " << ended.second;
}

INSTANTIATE_TEST_SUITE_P(Integrators, LanesEnd, ::testing::Values(VarianceCase{"pt", 1, 8.0}, VarianceCase{"lt", 8, 1.3}),
                         [](const auto& info) { return std::string(info.param.integrator); });

TEST(FluorescentLanes, EndIsRefusedWhereItIsNoExperiment) {
  auto scene = load("furnace_fluorescent.json");
  RenderSettings settings = scene->render;
  settings.fluorescentLanes = FluorescentLanes::End;
  for (const char* name : {"bdpt", "bdpt-shared", "bdpt-independent", "bdpt-mollified", "ppm"})
    EXPECT_THROW(makeIntegrator(name, *scene, settings), FluorescentLanesError) << name;
  for (const char* name : {"pt", "lt"}) EXPECT_NO_THROW(makeIntegrator(name, *scene, settings)) << name;
}

}  // namespace
}  // namespace kasha
