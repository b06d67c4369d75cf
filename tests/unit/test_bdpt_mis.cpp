// The strategy rules of docs/bdpt-mis.md §4 and the partition of unity of the weights (eq. 4).
#include <gtest/gtest.h>

#include "core/rng.h"
#include "integrators/bidirectional/mis.h"

namespace kasha::bidir {
namespace {

constexpr SpectralLobe E = SpectralLobe::Elastic, F = SpectralLobe::Fluorescent;

// A path x_0 … x_k with the given interior lobes and random positive densities.
constexpr Families kShared{true, false}, kIndependent{false, true}, kBoth{true, true};

FullPath randomPath(const std::vector<SpectralLobe>& interior, Families families, Rng& rng) {
  FullPath p;
  p.families = families;
  p.ownChoice = 0.01 + rng.uniform();
  p.cameraChoice = 0.01 + rng.uniform();
  p.sharedChoice = 0.01 + rng.uniform();
  p.sensorPdf = 0.01 + rng.uniform();
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
  for (int s = 0; s <= k; ++s) sum += misWeight(p, s, Variant::kStandard) + misWeight(p, s, Variant::kOwn);
  if (k >= 2) sum += misWeight(p, 1, Variant::kLightVertex);
  for (int s = 2; s < k; ++s) sum += misWeight(p, s, Variant::kMollified);
  for (int m = 1; m < k; ++m)
    sum += misWeight(p, m, Variant::kMerge) + misWeight(p, m, Variant::kMergeOwn) +
           misWeight(p, m, Variant::kMergeMollified) + misWeight(p, m, Variant::kMergeSplat);
  return sum;
}

TEST(BdptMis, WeightsArePartitionOfUnity) {
  Rng rng(5);
  const std::vector<std::vector<SpectralLobe>> lobes = {{}, {E}, {F}, {E, E}, {E, F}, {F, E}, {F, F, E}, {E, F, E, F}};
  for (const auto& l : lobes)
    for (Families m : {kShared, kIndependent, kBoth})
      for (int trial = 0; trial < 20; ++trial) {
        FullPath p = randomPath(l, m, rng);
        EXPECT_NEAR(weightSum(p), 1.0, 1e-6);
        p.mollifyWidth = 0.1 + 10.0 * rng.uniform();  // with the mollified strategies (§6)
        EXPECT_NEAR(weightSum(p), 1.0, 1e-6);
        // With vertex merging (§12), each kind's η its own.
        p.mergeEta = {0.1 + 10.0 * rng.uniform(), 0.1 + 10.0 * rng.uniform()};
        EXPECT_NEAR(weightSum(p), 1.0, 1e-6);
        p.connections = false;  // merges alone (bpm)
        EXPECT_NEAR(weightSum(p), 1.0, 1e-6);
      }
}

TEST(BdptMis, MergesAreExactWhereEachFamilySamplesTheGroupsOnce) {
  // docs/bdpt-mis.md §12: a shared-family merge needs a path of one group; an own-family merge a
  // fluorescent merge vertex, whatever the other lobes; bpm has no connections but the camera's hit.
  Rng rng(8);
  FullPath p = randomPath({E, F, E}, kBoth, rng);  // x_0 … x_4
  p.mergeEta = {2.0, 2.0};
  EXPECT_FALSE(strategyValid(p, 1, Variant::kMerge));
  EXPECT_FALSE(strategyValid(p, 1, Variant::kMergeOwn));
  EXPECT_TRUE(strategyValid(p, 2, Variant::kMergeOwn));
  EXPECT_FALSE(strategyValid(p, 0, Variant::kMergeOwn));  // x_0 is on the light
  EXPECT_FALSE(strategyValid(p, 4, Variant::kMergeOwn));  // x_4 is the pinhole
  p = randomPath({E, E}, kBoth, rng);
  p.mergeEta = {2.0, 2.0};
  EXPECT_TRUE(strategyValid(p, 1, Variant::kMerge));
  EXPECT_TRUE(strategyValid(p, 2, Variant::kMerge));
  EXPECT_FALSE(strategyValid(p, 2, Variant::kMergeOwn));
  EXPECT_FALSE(strategyValid(p, 2, Variant::kMergeMollified));  // no kernel
  p.mollifyWidth = 5.0;
  EXPECT_TRUE(strategyValid(p, 2, Variant::kMergeMollified));  // an own vertex through an elastic x_2
  FullPath q = randomPath({F}, kBoth, rng);
  q.mergeEta = {2.0, 2.0};
  q.mollifyWidth = 5.0;
  EXPECT_FALSE(strategyValid(q, 1, Variant::kMergeMollified));  // a fluorescent x_1 merges exactly
  EXPECT_TRUE(strategyValid(q, 1, Variant::kMergeOwn));
  // x_1, next to the camera, is the first gather vertex: the merge's density has η_g, the gather's
  // own: three times the radius, nine times the area, 81 times the weight against the camera's hit.
  const double before = misWeight(q, 1, Variant::kMergeOwn) / misWeight(q, 0, Variant::kStandard);
  q.mergeEta.gather = 18.0;
  auto gatherRatio = [&] { return misWeight(q, 1, Variant::kMergeOwn) / misWeight(q, 0, Variant::kStandard); };
  EXPECT_NEAR(gatherRatio(), 81.0 * before, 1e-4 * 81.0 * before);
  q.mergeEta.eta = 7.0;  // the other vertices' η: not x_1's
  EXPECT_NEAR(gatherRatio(), 81.0 * before, 1e-4 * 81.0 * before);
  q.mergeEta.gather = 0.0;
  EXPECT_FALSE(strategyValid(q, 1, Variant::kMergeOwn));
  // Behind a specular x_2 (x_3 the camera), x_1 is still the first gather vertex; x_1 of a path
  // whose x_2 is not specular is not.
  FullPath behindGlass = randomPath({F, E}, kBoth, rng);
  behindGlass.mergeEta = {0.0, 5.0};
  EXPECT_FALSE(strategyValid(behindGlass, 1, Variant::kMergeOwn));
  behindGlass.v[2].connectible = false;
  EXPECT_TRUE(strategyValid(behindGlass, 1, Variant::kMergeOwn));
  p.v[2].connectible = false;  // a specular vertex cannot merge
  EXPECT_FALSE(strategyValid(p, 2, Variant::kMerge));
  p.connections = false;
  EXPECT_TRUE(strategyValid(p, 0, Variant::kStandard));
  EXPECT_FALSE(strategyValid(p, 1, Variant::kStandard));
  EXPECT_FALSE(strategyValid(p, 3, Variant::kStandard));
  // A merge's density is both sides' at its vertex times η: against the connection that ends there.
  // The merged light vertex's subpath chose its light with the shared family's choice, next-event
  // estimation with its own.
  p = randomPath({E, E}, kShared, rng);
  p.mergeEta = {3.0, 5.0};
  const double ratio = misWeight(p, 1, Variant::kMerge) / misWeight(p, 1, Variant::kStandard);
  const double nee = p.cameraChoice * p.specCam1 * p.pdfNee * p.v[1].pdfCam * p.v[2].pdfCam;
  const double merge =
      p.sharedChoice * p.mergeEta.eta * p.v[0].pdfLight * p.v[1].pdfLight * p.v[1].pdfCam * p.v[2].pdfCam;
  EXPECT_NEAR(ratio, (merge / nee) * (merge / nee), 1e-6 * ratio);  // the weights are floats
}

TEST(BdptMis, AnOwnMergeAtTheCameraRaysHitTakesTheLightVertexsWavelength) {
  // docs/bdpt-mis.md §12: through an elastic x_{k−1} an own light vertex merges at its own
  // wavelength, the light side drawing every group's as t = 1 does (no sensor density), with η_g.
  Rng rng(12);
  FullPath p = randomPath({F, E}, kBoth, rng);  // x_0 … x_3
  p.mergeEta = {2.0, 7.0};
  EXPECT_TRUE(strategyValid(p, 2, Variant::kMergeSplat));
  EXPECT_FALSE(strategyValid(p, 1, Variant::kMergeSplat));  // not the camera ray's hit
  const double ratio = misWeight(p, 2, Variant::kMergeSplat) / misWeight(p, 3, Variant::kOwn);
  const double splat = p.mergeEta.gather * p.v[2].pdfCam / p.specLightLast;  // over t = 1's density
  EXPECT_NEAR(ratio, splat * splat, 1e-5 * ratio);
  p.sensorPdf *= 3.0;  // neither draws the last wavelength at the sensor
  EXPECT_NEAR(misWeight(p, 2, Variant::kMergeSplat) / misWeight(p, 3, Variant::kOwn), ratio, 1e-5 * ratio);
  FullPath q = randomPath({E, F}, kBoth, rng);
  q.mergeEta = {2.0, 7.0};
  EXPECT_FALSE(strategyValid(q, 2, Variant::kMergeSplat));  // a fluorescent x_2 merges at the camera's lanes
  p = randomPath({F, E}, kShared, rng);
  p.mergeEta = {2.0, 7.0};
  EXPECT_FALSE(strategyValid(p, 2, Variant::kMergeSplat));  // the own family's
}

TEST(BdptMis, MollifiedStrategiesJoinTwoElasticVerticesInTheIndependentFamily) {
  Rng rng(4);
  FullPath p = randomPath({E, E, F, E}, kIndependent, rng);  // x_0 … x_5 (camera)
  for (int s = 0; s <= 5; ++s) EXPECT_FALSE(strategyValid(p, s, Variant::kMollified)) << "off without a kernel";
  p.mollifyWidth = 2.0;
  EXPECT_TRUE(strategyValid(p, 2, Variant::kMollified));   // x_1 (E) – x_2 (E)
  EXPECT_FALSE(strategyValid(p, 3, Variant::kMollified));  // x_2 (E) – x_3 (F): exact, not mollified
  EXPECT_FALSE(strategyValid(p, 4, Variant::kMollified));  // x_3 (F) – x_4 (E)
  EXPECT_FALSE(strategyValid(p, 1, Variant::kMollified));  // only between two surface vertices
  EXPECT_FALSE(strategyValid(p, 5, Variant::kMollified));
  // Its density is the connection's (both sides' wavelength densities) times ε_h (eq. 6): the
  // weight ratio to strategy 3 follows from the layout alone.
  const double d2 = p.v[0].pdfLight * p.v[1].pdfLight * p.v[2].pdfCam * p.v[3].pdfCam * p.v[4].pdfCam * p.v[5].pdfCam;
  const double d3 = p.v[0].pdfLight * p.v[1].pdfLight * p.v[2].pdfLight * p.v[3].pdfCam * p.v[4].pdfCam * p.v[5].pdfCam;
  const double ratio = misWeight(p, 2, Variant::kMollified) / misWeight(p, 3, Variant::kOwn);
  EXPECT_NEAR(ratio, (2.0 * d2 / d3) * (2.0 * d2 / d3), 1e-5 * ratio);
  FullPath shared = p;
  shared.families = kShared;
  EXPECT_FALSE(strategyValid(shared, 2, Variant::kMollified));  // Shared joins elastic vertices exactly
  p.v[1].connectible = false;
  EXPECT_FALSE(strategyValid(p, 2, Variant::kMollified));
}

TEST(BdptMis, IndependentConnectionsNeedExactlyOneFluorescentEnd) {
  Rng rng(1);
  // x_0 x_1 x_2 x_3 x_4(camera): lobes at x_1..x_3 = E, F, E
  const FullPath p = randomPath({E, F, E}, kIndependent, rng);
  EXPECT_TRUE(strategyValid(p, 0, Variant::kStandard));
  EXPECT_TRUE(strategyValid(p, 1, Variant::kStandard));
  EXPECT_FALSE(strategyValid(p, 1, Variant::kLightVertex));  // x_1 is elastic
  EXPECT_TRUE(strategyValid(p, 2, Variant::kOwn));  // x_1 (E) – x_2 (F)
  EXPECT_TRUE(strategyValid(p, 3, Variant::kOwn));  // x_2 (F) – x_3 (E)
  EXPECT_TRUE(strategyValid(p, 4, Variant::kOwn));  // t = 1, x_3 elastic
  for (int s = 2; s <= 4; ++s) EXPECT_FALSE(strategyValid(p, s, Variant::kStandard)) << "no shared subpath";
  const FullPath q = randomPath({F, E, F}, kIndependent, rng);
  EXPECT_TRUE(strategyValid(q, 1, Variant::kLightVertex));
  EXPECT_TRUE(strategyValid(q, 2, Variant::kOwn));  // x_1 (F) – x_2 (E)
  EXPECT_TRUE(strategyValid(q, 3, Variant::kOwn));  // x_2 (E) – x_3 (F)
  EXPECT_TRUE(strategyValid(q, 4, Variant::kOwn));  // t = 1 samples x_3's fluorescent event itself
  const FullPath e = randomPath({E, E}, kIndependent, rng);
  EXPECT_FALSE(strategyValid(e, 2, Variant::kOwn));  // elastic–elastic joins two independent wavelengths
  EXPECT_TRUE(strategyValid(e, 3, Variant::kOwn));   // light tracing samples the single group
}

TEST(BdptMis, SharedBidirectionalStrategiesOnlyForElasticPaths) {
  Rng rng(2);
  const FullPath el = randomPath({E, E}, kShared, rng);
  for (int s = 0; s <= 3; ++s) EXPECT_TRUE(strategyValid(el, s, Variant::kStandard)) << s;
  for (int s = 0; s <= 3; ++s) EXPECT_FALSE(strategyValid(el, s, Variant::kOwn)) << "no own-wavelength subpath";
  EXPECT_FALSE(strategyValid(el, 1, Variant::kLightVertex));
  const FullPath fl = randomPath({E, F}, kShared, rng);
  EXPECT_TRUE(strategyValid(fl, 0, Variant::kStandard));
  EXPECT_TRUE(strategyValid(fl, 1, Variant::kStandard));
  EXPECT_FALSE(strategyValid(fl, 2, Variant::kStandard));
  EXPECT_FALSE(strategyValid(fl, 3, Variant::kStandard));
}

// Both families in one MIS (docs/bdpt-mis.md §5): an elastic path has the shared family's joins and
// t = 1 plus the own family's t = 1; a fluorescent one only the own family's exact joins.
TEST(BdptMis, UnifiedHasBothFamiliesWhereEachIsExact) {
  Rng rng(6);
  const FullPath el = randomPath({E, E, E}, kBoth, rng);  // x_0 … x_4 (camera)
  for (int s = 0; s <= 4; ++s) EXPECT_TRUE(strategyValid(el, s, Variant::kStandard)) << s;
  for (int s = 1; s <= 3; ++s) EXPECT_FALSE(strategyValid(el, s, Variant::kOwn)) << s;
  EXPECT_TRUE(strategyValid(el, 4, Variant::kOwn));  // t = 1 at the light's own wavelength
  const FullPath fl = randomPath({E, F, E}, kBoth, rng);
  for (int s = 2; s <= 4; ++s) EXPECT_FALSE(strategyValid(fl, s, Variant::kStandard)) << s;
  for (int s = 2; s <= 4; ++s) EXPECT_TRUE(strategyValid(fl, s, Variant::kOwn)) << s;
  const FullPath direct = randomPath({}, kBoth, rng);  // k = 1: the light seen by the camera
  EXPECT_TRUE(strategyValid(direct, 1, Variant::kStandard));
  EXPECT_TRUE(strategyValid(direct, 1, Variant::kOwn));
}

// The two t = 1 strategies of an elastic path differ only in who drew its one wavelength and chose
// its light: the sensor and the shared light subpath's choice (shared family), or the light-start
// strategy with its light (own family). Next-event estimation chooses the light with a choice of
// its own.
TEST(BdptMis, TheTwoLightTracingStrategiesDifferByTheirWavelengthDensities) {
  Rng rng(7);
  for (int k = 1; k <= 4; ++k) {
    FullPath p = randomPath(std::vector<SpectralLobe>(size_t(k - 1), E), kBoth, rng);
    const double ratio = misWeight(p, k, Variant::kOwn) / misWeight(p, k, Variant::kStandard);
    const double shared = p.sensorPdf * p.sharedChoice;
    EXPECT_NEAR(ratio, (p.ownChoice / shared) * (p.ownChoice / shared), 1e-5 * ratio) << k;
    // The shared t = 1 against the camera hitting the light: every factor written out.
    double light = shared, camera = p.sensorPdf;
    for (int i = 0; i < k; ++i) light *= p.v[size_t(i)].pdfLight;
    if (k >= 2) light *= p.specLightLast;
    for (int i = 0; i <= k; ++i) camera *= p.v[size_t(i)].pdfCam;
    const double r0 = misWeight(p, 0, Variant::kStandard) / misWeight(p, k, Variant::kStandard);
    EXPECT_NEAR(r0, (camera / light) * (camera / light), 1e-5 * r0) << k;
    if (k < 2) continue;
    // Next-event estimation against the camera hitting the light: x_1's spectral event, the light
    // point and its choice in place of the camera's density of x_0.
    const double nee = camera / p.v[0].pdfCam * p.specCam1 * p.pdfNee * p.cameraChoice;
    const double r1 = misWeight(p, 1, Variant::kStandard) / misWeight(p, 0, Variant::kStandard);
    EXPECT_NEAR(r1, (nee / camera) * (nee / camera), 1e-5 * r1) << k;
  }
}

TEST(BdptMis, DeltaVerticesCannotBeConnected) {
  Rng rng(3);
  FullPath p = randomPath({E, E}, kShared, rng);
  p.v[1].connectible = false;  // a mirror at x_1
  EXPECT_FALSE(strategyValid(p, 1, Variant::kStandard));
  EXPECT_FALSE(strategyValid(p, 2, Variant::kStandard));
  EXPECT_TRUE(strategyValid(p, 3, Variant::kStandard));
  EXPECT_NEAR(weightSum(p), 1.0, 1e-6);
}

}  // namespace
}  // namespace kasha::bidir
