// The strategy rules of docs/bdpt-mis.md §4 and the partition of unity of the weights (eq. 4).
#include <gtest/gtest.h>

#include "core/rng.h"
#include "integrators/bdpt/mis.h"

namespace kasha::bdpt {
namespace {

constexpr SpectralLobe E = SpectralLobe::Elastic, F = SpectralLobe::Fluorescent;

// A path x_0 … x_k with the given interior lobes and random positive densities.
FullPath randomPath(const std::vector<SpectralLobe>& interior, WavelengthMode mode, Rng& rng) {
  FullPath p;
  p.mode = mode;
  p.v.resize(interior.size() + 2);
  for (size_t i = 0; i < p.v.size(); ++i) {
    p.v[i].pdfLight = 0.01 + rng.uniform();
    p.v[i].pdfCam = 0.01 + rng.uniform();
    if (i > 0 && i + 1 < p.v.size()) p.v[i].lobe = interior[i - 1];
  }
  p.v.back().pdfCam = 1.0;
  p.specCam1 = 0.01 + rng.uniform();
  p.pdfNee = 0.01 + rng.uniform();
  p.lightSeenByPinhole = true;
  p.lightVertexConnectible = true;
  p.specLightLast = 0.01 + rng.uniform();
  return p;
}

double weightSum(const FullPath& p) {
  const int k = int(p.v.size()) - 1;
  double sum = 0.0;
  for (int s = 0; s <= k; ++s) sum += misWeight(p, s, SOne::kNee);
  if (k >= 2) sum += misWeight(p, 1, SOne::kLightVertex);
  return sum;
}

TEST(BdptMis, WeightsArePartitionOfUnity) {
  Rng rng(5);
  const std::vector<std::vector<SpectralLobe>> lobes = {{}, {E}, {F}, {E, E}, {E, F}, {F, E}, {F, F, E}, {E, F, E, F}};
  for (const auto& l : lobes)
    for (WavelengthMode m : {WavelengthMode::Shared, WavelengthMode::Independent})
      for (int trial = 0; trial < 20; ++trial) EXPECT_NEAR(weightSum(randomPath(l, m, rng)), 1.0, 1e-6);
}

TEST(BdptMis, IndependentConnectionsNeedExactlyOneFluorescentEnd) {
  Rng rng(1);
  // x_0 x_1 x_2 x_3 x_4(camera): lobes at x_1..x_3 = E, F, E
  const FullPath p = randomPath({E, F, E}, WavelengthMode::Independent, rng);
  EXPECT_TRUE(strategyValid(p, 0));
  EXPECT_TRUE(strategyValid(p, 1, SOne::kNee));
  EXPECT_FALSE(strategyValid(p, 1, SOne::kLightVertex));  // x_1 is elastic
  EXPECT_TRUE(strategyValid(p, 2));                       // x_1 (E) – x_2 (F)
  EXPECT_TRUE(strategyValid(p, 3));                       // x_2 (F) – x_3 (E)
  EXPECT_TRUE(strategyValid(p, 4));                       // t = 1, x_3 elastic
  const FullPath q = randomPath({F, E, F}, WavelengthMode::Independent, rng);
  EXPECT_TRUE(strategyValid(q, 1, SOne::kLightVertex));
  EXPECT_TRUE(strategyValid(q, 2));    // x_1 (F) – x_2 (E)
  EXPECT_TRUE(strategyValid(q, 3));    // x_2 (E) – x_3 (F)
  EXPECT_TRUE(strategyValid(q, 4));    // t = 1 samples x_3's fluorescent event itself
  const FullPath e = randomPath({E, E}, WavelengthMode::Independent, rng);
  EXPECT_FALSE(strategyValid(e, 2));   // elastic–elastic joins two independent wavelengths
  EXPECT_TRUE(strategyValid(e, 3));    // light tracing samples the single group
}

TEST(BdptMis, SharedBidirectionalStrategiesOnlyForElasticPaths) {
  Rng rng(2);
  const FullPath el = randomPath({E, E}, WavelengthMode::Shared, rng);
  for (int s = 0; s <= 3; ++s) EXPECT_TRUE(strategyValid(el, s)) << s;
  EXPECT_FALSE(strategyValid(el, 1, SOne::kLightVertex));
  const FullPath fl = randomPath({E, F}, WavelengthMode::Shared, rng);
  EXPECT_TRUE(strategyValid(fl, 0));
  EXPECT_TRUE(strategyValid(fl, 1, SOne::kNee));
  EXPECT_FALSE(strategyValid(fl, 2));
  EXPECT_FALSE(strategyValid(fl, 3));
}

TEST(BdptMis, DeltaVerticesCannotBeConnected) {
  Rng rng(3);
  FullPath p = randomPath({E, E}, WavelengthMode::Shared, rng);
  p.v[1].connectible = false;  // a mirror at x_1
  EXPECT_FALSE(strategyValid(p, 1, SOne::kNee));
  EXPECT_FALSE(strategyValid(p, 2));
  EXPECT_TRUE(strategyValid(p, 3));
  EXPECT_NEAR(weightSum(p), 1.0, 1e-6);
}

}  // namespace
}  // namespace kasha::bdpt
