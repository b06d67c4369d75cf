// Vertex merging's recursive MIS weights (docs/bdpt-mis.md §12) against the full recomputation over
// the whole path (integrators/bidirectional/mis.h): on subpaths traced as vcm traces them (both wavelength
// families on one light subpath where the scene fluoresces, lanes, elastic, fluorescent, glossy and
// specular vertices), every connection's and every merge's weight computed both ways must agree
// (relative 1e-5), with connections and merges (vcm) and merges alone (bpm), with and without the
// wavelength kernel that lets own light vertices merge through elastic lobes, and in media with the
// camera's query beams against photon points and photon beams (docs/media-beams.md); and the density of the
// connections alone that vcm's pilot weighs (docs/bdpt-mis.md §14) against the same recomputation.
#include <gtest/gtest.h>

#include "integrators/bidirectional/connect.h"
#include "integrators/bidirectional/merge.h"
#include "integrators/bidirectional/pilot_observer.h"
#include "integrators/bidirectional/subpath_mis.h"
#include "integrators/bidirectional/subpaths.h"
#include "scene/scene_loader.h"
#include "scene/wavelength_strategy.h"
#include "tests/support.h"
#include "tests/weight_checks.h"

namespace kasha::bidir {
namespace {

struct Case {
  const char* scene;
  bool connections;
  int lanes;
  float bandwidth = 0.0f;  // the wavelength kernel's half-width (nm): own merges through elastic lobes
  // η times this: ×100 makes the merges carry a share of the paths that connections make too, which
  // the check of the connections alone's density needs (at ×1 that share is mostly below 10⁻⁴).
  float etaScale = 1.0f;
  // Beams (docs/media-beams.md) whose weights the case must compare, at least: where the camera
  // starts inside the medium, so that its first segment is a query beam that sees the photons at the
  // camera's own wavelengths (elsewhere most query beams run at a camera path's excitation wavelength,
  // whose photons do not fluoresce into it, or start behind an index-matched boundary).
  int minBeams = 0;
};

std::string describe(const Case& c) {
  return std::string(c.scene) + (c.connections ? " vcm" : " bpm") + " lanes " + std::to_string(c.lanes) +
         (c.bandwidth > 0.0f ? " kernel" : "") + (c.etaScale != 1.0f ? " eta x" + std::to_string(int(c.etaScale)) : "");
}

class MergeWeights : public ::testing::TestWithParam<Case> {};

// The oracle, and for every connection's weight the density of the connections alone (vc's, the
// pilot's Alone::Connections: the recursive sums without their merge parts and without the
// mollified joins) against the full recomputation. By the power heuristic each strategy's weight is
// its c²·P² over the path's sum Σ, so the strategies vc lacks (the merges and the mollified joins)
// have the weights Σ_vcm − Σ_vc over Σ_vcm together: 1 − 1/ρ², with ρ = p_vcm/p_vc = √(Σ_vcm/Σ_vc).
// Summed from the full recomputation's weights, that share keeps its relative precision however
// small it is.
class WeightAndConnectionsOracle final : public MisObserver {
 public:
  test::WeightOracle weights;
  int compared = 0, inside = 0;  // ρ compared, and of those where the share is above 10⁻⁴
  void onWeight(const WeightEvent& e) override {
    weights.onWeight(e);
    if (isMerge(e.variant) || !(e.weight > 0.0f)) return;
    const FullPath path = e.layout(e.factors);
    const int k = int(path.v.size()) - 1;
    double share = 0.0;
    for (int i = 1; i < k; ++i)
      for (Variant v : {Variant::kMerge, Variant::kMergeOwn, Variant::kMergeMollified, Variant::kMollified,
                        Variant::kBeam, Variant::kBeamOwn, Variant::kPhotonBeam, Variant::kPhotonBeamOwn})
        share += misWeight(path, i, v);
    if (k >= 2) share += misWeight(path, k - 1, Variant::kMergeSplat);
    const double rho = densityOverAlone(Alone::Connections, e.total, e.factors, e.sum, 0.0);
    ++compared;
    inside += share > 1e-4;
    EXPECT_NEAR(1.0 - 1.0 / (rho * rho), share, 1e-4 * share + 1e-9)
        << "s = " << e.s << ", t = " << e.t << ", variant " << int(e.variant);
  }
};

TEST_P(MergeWeights, EqualTheFullRecomputation) {
  const Case& param = GetParam();
  const auto scene = loadScene(test::sourcePath(param.scene));
  const WavelengthSources sources(*scene);
  const WavelengthStrategy sensor(scene->render.wavelengths.sensor, sources, WavelengthSite::Sensor);
  const WavelengthStrategy light(scene->render.wavelengths.light, sources, WavelengthSite::LightStart);
  const Families families = familiesFor(*scene, WavelengthMode::Unified);
  const LightFirstStart lightFirst(*scene, scene->render.wavelengths.light);
  // η comparable with the other strategies' densities, so that merge weights fall inside (0, 1);
  // another at the first gather vertex, and one at collisions in media. With media the families
  // trace separate light subpaths (docs/media.md §5), and own vertices do not merge at the camera's
  // first vertex at their own wavelength (MergeEta::splat), as in vcm.
  const bool media = scene->hasMedia();
  const double eta = param.etaScale;
  Strategies strategies{param.connections, {3.0 * eta, 11.0 * eta, 5.0 * eta, 0.01, !media}};
  // And the camera's query beams against light vertices and flights in homogeneous media
  // (docs/media-beams.md).
  if (media) strategies.merge.beam = 2.0 * eta, strategies.merge.photonBeam = 7.0 * eta;
  const WalkSettings ws{6, 3, &light.density(), families.independent && !media ? &lightFirst : nullptr, strategies};
  std::vector<PathVertex> C, LS, LO;
  WeightAndConnectionsOracle observer;
  test::WeightOracle& oracle = observer.weights;
  LaneTables tables;
  std::vector<Splat> splats;
  std::vector<LightVertex> kept;
  RayCounter counter;
  test::WeightTally tally;
  std::vector<PhotonBeam> photonBeams;
  int merges = 0, beams = 0, photonBeamWeights = 0;
  for (uint32_t sample = 0; sample < 40000; ++sample) {
    Sampler rng(SamplerKind::Independent, 17, sample, 0);
    const Lanes lanes = sensorLanes(*scene, sensor.density(), rng.uniform(), param.lanes, tables,
                                    families.independent ? &light.density() : nullptr, ws.lightFirst);
    if (lanes.pdf[0] <= 0.0f) continue;
    const Vec2 film(rng.uniform() * float(scene->camera.width()), rng.uniform() * float(scene->camera.height()));
    traceCameraSubpath(*scene, film, lanes, ws, rng, counter, C);
    LS.clear(), LO.clear();
    int sharedLightVertices = 0;
    if (ws.lightFirst)
      sharedLightVertices = traceMergedLightSubpath(*scene, lanes, ws, rng, counter, LS, LO);
    else
      traceLightSubpath(*scene, LightFamily::Shared, lanes, ws, rng, counter, LS);
    if (media && families.independent) traceLightSubpath(*scene, LightFamily::Own, lanes, ws, rng, counter, LO);
    Context c{*scene, ws, families, lanes, sensor.density(), counter};
    c.sharedLightVertices = sharedLightVertices;
    c.bandwidth = param.bandwidth;
    c.observer = &observer;
    oracle.checks.clear();
    splats.clear();
    float radiance[kMaxLanes] = {};
    std::vector<SpectralSample> atLight;
    Vec3 xyz;
    if (param.connections) connectSubpaths(c, C, LS, LO, rng, splats, radiance, xyz);
    // Every light vertex merged with every camera vertex of its kind (surface, or collision in a
    // medium): the weights' algebra does not need them to be near each other.
    for (const std::vector<PathVertex>* L : {&LS, &LO}) {
      kept.clear();
      keepLightVertices(*L, L == &LO, *scene, strategies, kept);
      for (const LightVertex& v : kept)
        for (int t = 2; t <= int(C.size()) && v.depth + t - 2 <= ws.maxDepth; ++t)
          if (mergeable(C[size_t(t - 1)], true) && C[size_t(t - 1)].inMedium() == v.has(LightVertex::kMedium))
            merge(c, C, t, v, true, radiance, atLight, L);
      // And every light vertex in a medium with every query beam, somewhere along it, on every fourth
      // sample.
      for (const LightVertex& v : kept)
        for (int t = 2; sample % 4 == 0 && v.has(LightVertex::kMedium) && t <= int(C.size()) && v.depth + t - 2 <= ws.maxDepth; ++t)
          if (const std::optional<QueryBeam> q = queryBeam(c, C, t); q && std::isfinite(q->length))
            mergeBeam(c, C, t, *q, q->length * rng.uniform(), v, radiance, L);
      // And every photon beam with every query beam in its medium, somewhere along each, on every
      // 32nd sample (each light flight meets every query beam: the most expensive check here; the
      // furnaces still compare thousands).
      photonBeams.clear();
      if (sample % 32 == 0) keepPhotonBeams(*L, L == &LO, *scene, strategies, photonBeams);
      for (const PhotonBeam& b : photonBeams)
        for (int t = 2; t <= int(C.size()) && b.vertex.depth + t - 2 <= ws.maxDepth; ++t)
          if (const std::optional<QueryBeam> q = queryBeam(c, C, t); q && std::isfinite(q->length) && q->medium == b.medium)
            mergePhotonBeam(c, C, t, *q, b, {q->length * rng.uniform(), b.length * rng.uniform(), 1.0f}, radiance, L);
    }
    for (const test::WeightCheck& k : oracle.checks) beams += isBeam(Variant(k.variant)) && !isPhotonBeam(Variant(k.variant));
    for (const test::WeightCheck& k : oracle.checks) photonBeamWeights += isPhotonBeam(Variant(k.variant));
    for (const test::WeightCheck& k : oracle.checks) merges += isMerge(Variant(k.variant));
    ASSERT_TRUE(tally.add(oracle.checks, sample)) << describe(param);
  }
  EXPECT_GT(merges, 2000) << describe(param);
  EXPECT_GE(beams, param.minBeams) << describe(param);
  EXPECT_GE(photonBeamWeights, param.minBeams) << describe(param);
  // The connections alone's density (vcm's pilot) on paths that merges sample too.
  if (param.etaScale > 1.0f) EXPECT_GT(observer.inside, 200) << describe(param) << ": " << observer.compared << " compared";
  // With connections, more than 2000 of them besides the merges.
  tally.expectPower(param.connections ? merges + 2000 : merges - 1, describe(param));
}

INSTANTIATE_TEST_SUITE_P(
    Scenes, MergeWeights,
    ::testing::Values(Case{"scenes/cornell_uv.json", true, 4},     // both families, UV spot, fluorescence
                      Case{"scenes/cornell_uv.json", false, 4},
                      Case{"scenes/cornell_uv.json", true, 4, 20.0f},  // and the wavelength kernel
                      Case{"scenes/cornell_uv.json", false, 1, 20.0f},
                      Case{"scenes/cornell_uv.json", true, 1},
                      Case{"scenes/cornell_glossy.json", true, 4},  // glossy, elastic: the shared family alone
                      Case{"scenes/cornell_glossy.json", false, 1},
                      Case{"scenes/uv_caustic.json", true, 4},      // glass: specular vertices
                      Case{"scenes/validation/furnace_fluorescent.json", true, 4},  // a fluorescent emitter
                      Case{"scenes/validation/furnace_fluorescent.json", false, 4},
                      Case{"scenes/validation/smooth_sphere_distant.json", true, 4},  // a distant light
                      Case{"scenes/validation/single_sphere_environment.json", true, 4},  // environment
                      // Collisions in media (docs/media.md §6): a fluorescent slab under a distant
                      // light, a scattering fluorescent medium, a dye behind glass.
                      Case{"scenes/validation/media_slab.json", true, 1},
                      Case{"scenes/validation/media_fluorescent_furnace.json", true, 1, 0.0f, 1.0f, 500},
                      Case{"scenes/validation/media_fluorescent_furnace.json", false, 1, 0.0f, 1.0f, 500},  // the merges' algebra alone
                      Case{"scenes/validation/media_scattering_furnace.json", true, 4, 0.0f, 1.0f, 500},  // elastic: shared beams
                      Case{"scenes/fluorescein_cuvette.json", true, 1},
                      // Lanes in media: ended at a flight through a medium.
                      Case{"scenes/validation/media_slab.json", true, 4},
                      Case{"scenes/validation/media_fluorescent_furnace.json", true, 4, 0.0f, 1.0f, 500},
                      Case{"scenes/fluorescein_cuvette.json", true, 4},
                      Case{"scenes/tonic_water.json", true, 4},
                      // The connections alone's density where merges carry a share of the paths.
                      Case{"scenes/cornell_uv.json", true, 4, 20.0f, 100.0f},  // with the mollified joins
                      Case{"scenes/tonic_water.json", true, 4, 0.0f, 100.0f}),
    [](const ::testing::TestParamInfo<Case>& info) {
      std::string name = describe(info.param);
      for (char& ch : name)
        if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
      return name;
    });

}  // namespace
}  // namespace kasha::bidir
