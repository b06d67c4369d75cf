// Photon beams (integrators/bidirectional/photon_beam.h, docs/media-beams.md eqs. B4, B5):
// - a beam's light vertex at the end of its flight, where the flight collided, is the light vertex the
//   walk kept there (keepLightVertices): the same throughput times the flight's weight, densities and
//   sums, though vertexAlong computes them from the beam's origin alone;
// - the query of beams near a segment (integrators/beams_near_segments.h) finds what a brute-force
//   search finds;
// - the chord of a query through a beam's cylinder is the length of the query inside it, as a fine
//   march along the query measures it.
#include <gtest/gtest.h>

#include <random>

#include "integrators/beams_near_segments.h"
#include "integrators/bidirectional/merge.h"
#include "integrators/bidirectional/photon_beam.h"
#include "integrators/bidirectional/subpaths.h"
#include "scene/scene_loader.h"
#include "scene/wavelength_strategy.h"
#include "tests/support.h"

namespace kasha::bidir {
namespace {

void expectRelative(double actual, double expected, const char* what, int beam) {
  EXPECT_NEAR(actual, expected, 1e-3 * std::abs(expected) + 1e-12) << what << ", beam " << beam;
}

void expectSums(const MisSums& a, const MisSums& b, int beam) {
  expectRelative(a.hit, b.hit, "hit", beam);
  expectRelative(a.nee, b.nee, "nee", beam);
  expectRelative(a.shared, b.shared, "shared", beam);
  expectRelative(a.own, b.own, "own", beam);
  expectRelative(a.mollified, b.mollified, "mollified", beam);
  expectRelative(a.ownSplat, b.ownSplat, "ownSplat", beam);
  expectRelative(a.mergeShared, b.mergeShared, "mergeShared", beam);
  expectRelative(a.mergeOwn, b.mergeOwn, "mergeOwn", beam);
  expectRelative(a.mergeMollified, b.mergeMollified, "mergeMollified", beam);
}

struct EndCase {
  const char* scene;
  int minFromCollisions;  // beams from a collision: their sums carry the origin's own query beam
};

class PhotonBeamEnd : public ::testing::TestWithParam<EndCase> {};

TEST_P(PhotonBeamEnd, IsTheLightVertexTheFlightMadeThere) {
  const auto scene = loadScene(test::sourcePath(GetParam().scene));
  const WavelengthSources sources(*scene);
  const WavelengthStrategy sensor(scene->render.wavelengths.sensor, sources, WavelengthSite::Sensor);
  const WavelengthStrategy light(scene->render.wavelengths.light, sources, WavelengthSite::LightStart);
  const Families families = familiesFor(*scene, WavelengthMode::Unified);
  // Every kind of merge and beam, so that every term of the sums is there to compare.
  Strategies strategies{true, {3.0, 11.0, 5.0, 0.01, false}};
  strategies.merge.beam = 2.0, strategies.merge.photonBeam = 7.0;
  const WalkSettings ws{8, 3, &light.density(), nullptr, strategies};
  LaneTables tables;
  RayCounter counter;
  std::vector<PathVertex> L;
  std::vector<LightVertex> kept;
  std::vector<PhotonBeam> beams;
  int compared = 0, originInMedium = 0;
  for (uint32_t sample = 0; sample < 4000; ++sample) {
    Sampler rng(SamplerKind::Independent, 23, sample, 0);
    const Lanes lanes = sensorLanes(*scene, sensor.density(), rng.uniform(), 4, tables,
                                    families.independent ? &light.density() : nullptr, nullptr);
    for (const LightFamily family : {LightFamily::Shared, LightFamily::Own}) {
      if (family == LightFamily::Own && !families.independent) continue;
      L.clear(), kept.clear(), beams.clear();
      traceLightSubpath(*scene, family, lanes, ws, rng, counter, L);
      const bool own = family == LightFamily::Own;
      keepLightVertices(L, own, *scene, strategies, kept);
      keepPhotonBeams(L, own, *scene, strategies, beams);
      for (const PhotonBeam& b : beams) {
        const PathVertex& end = L[b.vertex.depth];
        if (!end.inMedium()) continue;
        const auto real = std::find_if(kept.begin(), kept.end(), [&](const LightVertex& v) { return v.depth == b.vertex.depth; });
        if (real == kept.end()) continue;
        const LightVertex along = vertexAlong(*scene, b, b.length).vertex;
        const int i = compared++;
        originInMedium += b.originInMedium;
        for (int k = 0; k < 3; ++k) {
          EXPECT_NEAR(along.p[k], real->p[k], 1e-4f * (1.0f + std::abs(real->p[k]))) << "position, beam " << i;
          EXPECT_NEAR(along.wi[k], real->wi[k], 1e-4f) << "direction, beam " << i;
        }
        expectRelative(along.beta[0] * end.flightWeight, real->beta[0], "throughput", i);
        expectRelative(along.pdfFwd, real->pdfFwd, "pdfFwd", i);
        expectRelative(along.pdfPrev, real->pdfPrev, "pdfPrev", i);
        expectRelative(along.prevGeometry, real->prevGeometry, "prevGeometry", i);
        expectSums(along.sums, real->sums, i);
        EXPECT_EQ(along.lambda, real->lambda) << "beam " << i;
        EXPECT_EQ(along.lane, real->lane) << "beam " << i;
        EXPECT_EQ(int(along.flags), int(real->flags)) << "beam " << i;
      }
    }
  }
  EXPECT_GT(compared, 100) << GetParam().scene;
  EXPECT_GE(originInMedium, GetParam().minFromCollisions) << GetParam().scene;
}

INSTANTIATE_TEST_SUITE_P(MediaScenes, PhotonBeamEnd,
                         ::testing::Values(EndCase{"scenes/validation/media_scattering_furnace.json", 100},
                                           EndCase{"scenes/validation/media_fluorescent_furnace.json", 100},
                                           EndCase{"scenes/tonic_water.json", 0}),  // in centimetres
                         [](const ::testing::TestParamInfo<EndCase>& info) {
                           std::string name = info.param.scene;
                           name = name.substr(name.rfind('/') + 1);
                           name = name.substr(0, name.find('.'));
                           return name;
                         });

// The distance from p to the segment a + s·w, s in [0, length].
float distanceToSegment(const Vec3& p, const BeamsNearSegments::Beam& b) {
  const float s = std::clamp(glm::dot(p - b.a, b.w), 0.0f, b.length);
  return glm::length(p - (b.a + s * b.w));
}

TEST(BeamsNearSegments, FindWhatABruteForceSearchFinds) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  auto direction = [&] { return glm::normalize(Vec3(u(rng) - 0.5f, u(rng) - 0.5f, u(rng) - 0.5f)); };
  std::vector<BeamsNearSegments::Beam> beams(600);
  for (auto& b : beams) b = {Vec3(u(rng), u(rng), u(rng)), direction(), 0.3f * u(rng)};
  const float r = 0.04f;
  const BeamsNearSegments query(beams, r);
  std::vector<uint32_t> found;
  size_t total = 0, inside = 0;
  for (int i = 0; i < 600; ++i) {
    // Every fourth segment starts on a beam and is shorter than r: inside its capsule.
    const bool shortOne = i % 4 == 0;
    const Vec3 o = shortOne ? beams[size_t(i)].a + 0.5f * beams[size_t(i)].length * beams[size_t(i)].w
                            : Vec3(u(rng), u(rng), u(rng)) * 1.4f - 0.2f;
    const Vec3 d = direction();
    const float length = shortOne ? 0.5f * r * u(rng) : 1.2f * u(rng);
    query.near(o, d, length, found);
    // Every beam within r of the segment (by a fine march along it) must be found; those found must
    // come within r of it (up to the march's step).
    constexpr int kSteps = 200;
    for (size_t j = 0; j < beams.size(); ++j) {
      float closest = 1e9f;
      for (int k = 0; k <= kSteps; ++k) closest = std::min(closest, distanceToSegment(o + d * (length * k / kSteps), beams[j]));
      const bool listed = std::binary_search(found.begin(), found.end(), uint32_t(j));
      if (closest < 0.999f * r) {
        EXPECT_TRUE(listed) << "segment " << i << ", beam " << j;
      }
      if (listed) {
        EXPECT_LT(closest, r + length / kSteps) << "segment " << i << ", beam " << j;
      }
    }
    total += found.size();
    inside += shortOne ? found.size() : 0;
  }
  EXPECT_GT(total, 300u);
  EXPECT_GT(inside, 100u);
}

TEST(BeamCrossing, ChordIsTheQueryInsideTheCylinder) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  auto direction = [&] { return glm::normalize(Vec3(u(rng) - 0.5f, u(rng) - 0.5f, u(rng) - 0.5f)); };
  const float r = 0.1f;
  int crossings = 0;
  for (int i = 0; i < 3000; ++i) {
    QueryBeam q;
    q.origin = Vec3(u(rng), u(rng), u(rng)) * 0.4f;
    q.w = direction();
    q.length = 0.6f * u(rng);
    PhotonBeam b;
    b.origin = Vec3(u(rng), u(rng), u(rng)) * 0.4f;
    b.w = direction();
    b.length = 0.6f * u(rng);
    // The flat-capped cylinder: within r of the beam's line, projecting inside the beam.
    constexpr int kSteps = 20000;
    double inside = 0.0;
    for (int k = 0; k < kSteps; ++k) {
      const Vec3 x = q.origin + q.w * (q.length * (k + 0.5f) / kSteps);
      const float s = glm::dot(x - b.origin, b.w);
      const Vec3 across = x - (b.origin + s * b.w);
      inside += s >= 0.0f && s <= b.length && glm::dot(across, across) < r * r;
    }
    inside *= q.length / kSteps;
    const float uChord = u(rng);
    const std::optional<BeamCrossing> x = crossing(q, b, r, uChord);
    if (!x) {
      EXPECT_LT(inside, 2.0 * q.length / kSteps) << "query " << i;
      continue;
    }
    ++crossings;
    EXPECT_NEAR(x->chord, inside, 2.0 * q.length / kSteps + 1e-3 * inside) << "query " << i;
    // Its point: uChord along the chord, inside the cylinder.
    const Vec3 at = q.origin + x->t * q.w, onBeam = b.origin + x->s * b.w;
    EXPECT_LT(glm::length(at - onBeam), r * 1.0001f) << "query " << i;
    EXPECT_NEAR(glm::dot(at - b.origin, b.w), x->s, 1e-4f) << "query " << i;
  }
  EXPECT_GT(crossings, 200);
}

}  // namespace
}  // namespace kasha::bidir
