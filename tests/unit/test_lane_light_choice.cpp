// The light choice for wavelength lanes (docs/wavelength-sampling.md "Choosing the light"):
// LaneLightTable (light subpaths' and BDPT's), and next-event estimation's LaneLightChoice with the
// lanes' importance (laneImportance).
// - without the power share LaneLightChoice is the mixture over the lanes, as LaneLightTable is,
//   and LaneLightTable draws each light with the probability it reports;
// - with it, a lane inside a strong narrow UV light takes that light, unless its importance is 0;
// - select() chooses each light with the probability it reports;
// - laneImportance follows each lane's weight: equal for fluorescent lanes drawn from the
//   material's own density (Kasha's rule), ∝ a(λ)/p(λ) for a strategy's, throughput × scale for
//   elastic lanes.
// The closed form of a plane under a UV and a white distant light (closed_form_tests.cpp,
// SingleScatteringPlaneUnderUvAndWhiteLights) checks that pt and ppm stay unbiased with it.
#include <gtest/gtest.h>

#include <memory>

#include "integrators/lane_light_choice.h"
#include "tests/closed_form_support.h"

namespace kasha {
namespace {

using namespace test;

Bsdf bsdfAt(const Scene& scene, std::span<const float> lanes) {
  const Frame world{Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)};
  return scene.materials.at(0)->bsdf(HitContext{Vec2(0.0f), world, world, lanes});
}

// single_plane_uv_white.json: light 0 a distant Gaussian at 365 nm (scale 20), light 1 a dim white
// distant light (0.05). Lane 0 sits inside the UV band; at the others only the white light emits.
constexpr float kLanes[4] = {365.0f, 450.0f, 550.0f, 650.0f};

// (1/N)·Σ_k Φ_l(λ_k)/Φ(λ_k), computed here from the lights' powers.
float laneMixture(const Scene& scene, size_t light) {
  float sum = 0.0f;
  for (const float lambda : kLanes) {
    float total = 0.0f;
    for (const auto& l : scene.lights) total += l->power(lambda);
    sum += scene.lights[light]->power(lambda) / total;
  }
  return sum / 4.0f;
}

// select() over a fine grid of u chooses each of the two lights with the probability it reports.
template <class Choice>
void expectSelectionFollowsProbabilities(const Choice& table) {
  const int grid = 100000;
  int chosen[2] = {};
  for (int i = 0; i < grid; ++i) {
    const auto [l, p] = table.select((float(i) + 0.5f) / float(grid));
    ASSERT_LT(l, 2u);
    EXPECT_EQ(p, table.probability(l));
    ++chosen[l];
  }
  for (size_t l = 0; l < 2; ++l) EXPECT_NEAR(float(chosen[l]) / float(grid), table.probability(l), 2.0f / float(grid));
}

TEST(LaneLightChoice, WithoutThePowerShareItIsEachLanesMixture) {
  const auto scene = load("single_plane_uv_white.json");
  LaneLightChoice choice;
  const float equal[4] = {1.0f, 1.0f, 1.0f, 1.0f};
  choice.reset(*scene, kLanes, equal, 0.0f);
  LaneLightTable table;
  table.reset(*scene, kLanes);
  for (size_t l = 0; l < 2; ++l) {
    EXPECT_NEAR(choice.probability(l), laneMixture(*scene, l), 1e-6f) << "light " << l;
    EXPECT_NEAR(table.probability(l), laneMixture(*scene, l), 1e-6f) << "light " << l;
  }
  // Each lane gets a quarter: the UV light only through lane 0's quarter.
  EXPECT_LT(table.probability(0), 0.25f);
}

TEST(LaneLightTable, SelectChoosesEachLightWithItsProbabilityAndEachLaneAsTheSelector) {
  const auto scene = load("single_plane_uv_white.json");
  LaneLightTable table;
  table.reset(*scene, kLanes, /*perLane=*/true);
  expectSelectionFollowsProbabilities(table);
  for (int k = 0; k < 4; ++k)
    for (size_t l = 0; l < 2; ++l)
      EXPECT_NEAR(table.laneProbability(l, k), scene->lightSelector->probability(l, kLanes[k]), 1e-6f);
}

TEST(LaneLightChoice, ThePowerShareFollowsTheLanesWeightedPower) {
  const auto scene = load("single_plane_uv_white.json");
  const Light& uv = *scene->lights[0];
  const Light& white = *scene->lights[1];
  ASSERT_GT(uv.power(365.0f), 100.0f * white.power(365.0f));  // the scene is what the test needs
  const float alpha = kNeeLightsByPower;
  float uvPower = 0.0f, all = 0.0f, uvShare = 0.0f;
  for (const float l : kLanes) {
    uvPower += uv.power(l);
    all += uv.power(l) + white.power(l);
    uvShare += uv.power(l) / (uv.power(l) + white.power(l)) / 4.0f;
  }
  LaneLightChoice table;
  const float equal[4] = {1.0f, 1.0f, 1.0f, 1.0f};
  table.reset(*scene, kLanes, equal);
  EXPECT_NEAR(table.probability(0), alpha * uvPower / all + (1.0f - alpha) * uvShare, 1e-5f);
  EXPECT_NEAR(table.probability(0) + table.probability(1), 1.0f, 1e-6f);
  EXPECT_GT(table.probability(0), 0.85f);  // lane 0's light, thousands of times brighter
  // A lane of importance 0 asks for nothing: the UV light keeps only the defensive share.
  const float noUv[4] = {0.0f, 1.0f, 1.0f, 1.0f};
  table.reset(*scene, kLanes, noUv);
  EXPECT_NEAR(table.probability(0), (1.0f - alpha) * uvShare, 1e-5f);
  EXPECT_GT(table.probability(0), 0.0f);
}

TEST(LaneLightChoice, SelectChoosesEachLightWithItsProbability) {
  const auto scene = load("single_plane_uv_white.json");
  LaneLightChoice table;
  const float importance[4] = {0.5f, 2.0f, 1.0f, 3.0f};
  table.reset(*scene, kLanes, importance);
  expectSelectionFollowsProbabilities(table);
}

TEST(LaneImportance, FluorescentLanesOfTheMaterialsDensityWeighTheSame) {
  // furnace_overlap.json: every lane below can fluoresce. By Kasha's rule the material's excitation
  // density given any lane is ∝ a(λ), so each new lane's weight a(λ_k)/Σ_m n_m q_m(λ_k) is the same.
  const auto scene = load("furnace_overlap.json");
  const float known[4] = {480.0f, 500.0f, 520.0f, 540.0f};
  const float before[4] = {1.0f, 2.0f, 3.0f, 4.0f};
  const Bsdf bsdf = bsdfAt(*scene, known);
  for (const float u : {0.0f, 0.003f, 0.01f}) {
    const LaneEvent e = sampleLaneEvent(bsdf, TransportMode::Radiance, known, 4, u);
    ASSERT_EQ(e.lobe, SpectralLobe::Fluorescent);
    float importance[4];
    laneImportance(bsdf, TransportMode::Radiance, known, before, e, importance);
    ASSERT_GT(importance[0], 0.0f);
    for (int k = 1; k < e.n; ++k) EXPECT_NEAR(importance[k] / importance[0], 1.0f, 1e-4f) << "lane " << k;
  }
}

TEST(LaneImportance, FluorescentLanesOfAStrategyWeighAsAbsorptionOverDensity) {
  const auto scene = load("furnace_overlap.json");
  const JungBbrrdf& m = jung(*scene);
  const float known[4] = {480.0f, 500.0f, 520.0f, 540.0f};
  const float before[4] = {1.0f, 1.0f, 1.0f, 1.0f};
  const Bsdf bsdf = bsdfAt(*scene, known);
  // A density ∝ 1 + (λ − 300)/100 over the scene's range: not ∝ a, so the lanes differ.
  WavelengthDensity ramp;
  ramp.add(std::make_shared<SpectralDistribution>(Spectrum::piecewiseLinear({300.0f, 830.0f}, {1.0f, 6.3f}), scene->range),
           1.0f);
  const LaneEvent e = sampleLaneEvent(bsdf, TransportMode::Radiance, known, 4, 0.0f, &ramp);
  ASSERT_EQ(e.lobe, SpectralLobe::Fluorescent);
  float importance[4];
  laneImportance(bsdf, TransportMode::Radiance, known, before, e, importance);
  int compared = 0;
  for (int k = 1; k < e.n; ++k) {
    if (!(m.a(e.lambda[k]) > 0.0f && m.a(e.lambda[0]) > 0.0f)) continue;
    const float expected = (m.a(e.lambda[k]) / ramp.pdf(e.lambda[k])) / (m.a(e.lambda[0]) / ramp.pdf(e.lambda[0]));
    EXPECT_NEAR(importance[k] / importance[0], expected, 1e-3f * expected) << "lane " << k;
    ++compared;
  }
  EXPECT_GT(compared, 0);
}

TEST(LaneImportance, ElasticLanesWeighAsTheirThroughput) {
  const auto scene = load("furnace_overlap.json");
  const float known[4] = {480.0f, 500.0f, 520.0f, 540.0f};
  const float before[4] = {1.0f, 2.0f, 3.0f, 4.0f};
  const Bsdf bsdf = bsdfAt(*scene, known);
  const LaneEvent e = sampleLaneEvent(bsdf, TransportMode::Radiance, known, 4, 0.999f);
  ASSERT_EQ(e.lobe, SpectralLobe::Elastic);
  float importance[4];
  laneImportance(bsdf, TransportMode::Radiance, known, before, e, importance);
  for (int k = 0; k < e.n; ++k) EXPECT_FLOAT_EQ(importance[k], before[k] * e.scale[k]);
}

}  // namespace
}  // namespace kasha
