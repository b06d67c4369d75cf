#include "integrators/bidirectional/merge.h"

#include <algorithm>

#include "integrators/bidirectional/connect_parts.h"
#include "integrators/bidirectional/path_media.h"
#include "integrators/bidirectional/photon_beam.h"
#include "integrators/progressive_schedule.h"

namespace kasha::bidir {

namespace {

// What a merge of v with b = C[t−1] through `lobe` (λ_in arriving from v, λ_out leaving towards
// the camera) needs for its weight besides its own term (docs/bdpt-mis.md §12): the sums of every
// other strategy of the path, and the densities of b's neighbours the merge recomputes.
struct MergeSums {
  MisSums total;
  double specCam = 0.0, specLight = 0.0;  // b's event: the camera side's and the light side's
  double pCamPrev = 0.0;                  // the camera side's density of x_{m−1}, sampled at x_m
  double pLightNext = 0.0;                // the light side's of x_{m+1} (t > 2)
  double beamSine = 0.0;                  // sin θ between x_m's two segments (PathVertex::beamSine)
};

// The light side's beam ratio at the merge of v with b (PathVertex::lightBeam): over v's arrival, in
// b's medium (a collision merges with a light vertex in its own).
double lightBeamOf(const Context& c, const LightVertex& v, const PathVertex& b) {
  return v.has(LightVertex::kLightBeam) && b.inMedium() ? inverseSigmaT(c.scene, b.medium, v.lambda) : 0.0;
}

MergeSums mergeSums(const Context& c, const std::vector<PathVertex>& C, int t, const LightVertex& v,
                    SpectralLobe lobe, float lambdaIn, float lambdaOut, bool gather, const Vec3& bWi, const Vec3& bWo) {
  const PathVertex& b = C[size_t(t - 1)];
  const PathVertex& bNext = C[size_t(t - 2)];
  const Bsdf& fb = *b.bsdf;
  const Strategies& st = c.walk.strategies;
  const int m = v.depth;
  MergeSums r;
  r.specCam = fb.spectralPdf(TransportMode::Radiance, lambdaOut, lambdaIn, lobe);
  r.specLight = fb.spectralPdf(TransportMode::Importance, lambdaIn, lambdaOut, lobe);
  r.pCamPrev =
      r.specCam * fb.directionPdf({TransportMode::Radiance, lobe, lambdaIn, lambdaOut}, bWo, bWi) * v.prevGeometry;
  // The light side (eq. 10 from the sum the light vertex kept): the strategy s' = m, whose
  // connection ends at x_m, with the merges at x_m.
  const SpectralLobe prevLobe =
      v.has(LightVertex::kPrevFluorescent) ? SpectralLobe::Fluorescent : SpectralLobe::Elastic;
  // sin θ between the light's arrival and the camera side's, both in b's frame (only where a photon
  // beam could merge).
  if (st.merge.photonBeam > 0.0 && b.inMedium()) r.beamSine = glm::length(glm::cross(bWi, bWo));
  const MisSums mLast = mergeMultiplicity(true, lobe, v.pdfFwd, gather, t == 2, st, b.inMedium(), b.cameraBeam,
                                          photonBeamRatio(lightBeamOf(c, v, b), r.beamSine)) +
                        (m == 1 ? firstVertexMultiplicity(true, lobe, r.specCam, v.has(LightVertex::kFiniteLight), st)
                                : joinMultiplicity(v.has(LightVertex::kPrevConnectible), prevLobe, lobe, st));
  const double rPrev = densityRatio(r.pCamPrev, v.pdfPrev);
  r.total = extend(v.sums * (rPrev * rPrev), densityRatio(b.pdfFwd, v.pdfFwd), mLast);
  // The strategy s' = m + 1 (x_m the last light vertex), and the camera side beyond it.
  if (t == 2) {
    r.total = r.total + lightTracingMultiplicity(true, r.specLight, st);
  } else {
    const double pdf = r.specLight * fb.directionPdf({TransportMode::Importance, lobe, lambdaIn, lambdaOut}, bWi, bWo);
    r.pLightNext = toArea(c.scene, float(pdf), b, bNext) *
                   flightFactor(c.scene, TransportMode::Importance, b.arrival, bNext, lambdaOut);
    r.total = r.total + joinMultiplicity(bNext.joinable(false), lobe, bNext.lobe, st) +
              cameraSum(c, C, t - 1, r.pLightNext, cameraMultiplicity(C, t - 2, st, false), C[size_t(t - 3)].pdfRev);
  }
  return r;
}

// How a merge meets the camera side: at its vertex C[t−1] (a point), or along its query beam, with a
// photon point or a photon beam (docs/media-beams.md).
struct Along {
  enum class Kind : uint8_t { Point, QueryBeam, PhotonBeam } kind = Kind::Point;
  float chord = 1.0f;             // a photon beam's: the query beam's chord through its cylinder
  double originCameraBeam = 0.0;  // a photon beam's: R_C/F_C at its origin x_{m−1}, from x_m
};

// The merge's path laid out for the full recomputation (FullPathLayout, the test oracle), with factors g.
FullPath fullPath(const Context& c, const std::vector<PathVertex>& C, int t, const LightVertex& v,
                  const std::vector<PathVertex>* lightPath, SpectralLobe lobe, const MergeSums& r, const MisFactors& g,
                  const Along& along) {
  const std::vector<PathVertex>& L = *lightPath;
  const int m = v.depth;
  FullPath fp = layout(c, &L, m + 1, C, t - 1, storedLightEnd(L, m + 1), g, false);
  if (along.kind == Along::Kind::PhotonBeam) {  // x_m, a collision on the light subpath's flight into L[m]
    FullVertex& x = fp.v[size_t(m)];
    x.pdfLight = v.pdfFwd;
    x.connectible = x.mergeable = x.volume = true;
    fp.v[size_t(m - 1)].cameraBeam = along.originCameraBeam;
  }
  fp.v[size_t(m)].lobe = lobe;
  fp.v[size_t(m)].pdfCam = C[size_t(t - 1)].pdfFwd;
  fp.v[size_t(m)].cameraBeam = C[size_t(t - 1)].cameraBeam;
  fp.v[size_t(m)].lightBeam = lightBeamOf(c, v, C[size_t(t - 1)]);
  fp.v[size_t(m)].beamSine = r.beamSine;
  fp.v[size_t(m - 1)].pdfCam = r.pCamPrev;
  if (t > 2) fp.v[size_t(m + 1)].pdfLight = r.pLightNext;
  fp.specCam1 = m == 1 ? r.specCam : specCamera(L[1], L[1].lobe, L[1].lambda, L[1].lambdaNext);
  fp.specLightLast = t == 2 ? r.specLight : specLightLast(C[1], C[1].lobe, C[1].lambdaNext);
  return fp;
}

// Whether the path of a merge through `lobe` has one group: a property of the path, whichever
// family made it.
bool oneGroup(const LightVertex& v, const PathVertex& b, SpectralLobe lobe) {
  return lobe == SpectralLobe::Elastic && v.has(LightVertex::kElasticBefore) && b.elasticBefore;
}

// Merges v with b = C[t−1] at lanes [k0, k1) (docs/bdpt-mis.md §12; `gather`: b is the path's first
// gather vertex, merge.h for withinRadius): lambdaB the wavelength of b's densities (and of an own
// vertex's one lane), betaB b's throughput per lane, times laneFactor.
void mergeLanes(const Context& c, const std::vector<PathVertex>& C, int t, const LightVertex& v, bool withinRadius,
                const Along& along, bool gather, int k0, int k1, float lambdaB, const float* betaB, float laneFactor,
                float* out, const std::vector<PathVertex>* lightPath) {
  const PathVertex& b = C[size_t(t - 1)];
  const PathVertex& bNext = C[size_t(t - 2)];
  const bool own = v.has(LightVertex::kOwn);
  // The exact merges (docs/bdpt-mis.md §12): a shared vertex through the elastic lobe at the
  // camera's (the pass's) wavelengths; an own vertex through the fluorescent lobe, from its
  // wavelength to the camera's, or through the elastic lobe and the wavelength kernel.
  struct Kind {
    SpectralLobe lobe;
    Variant variant;
  };
  // Against a query beam (docs/media-beams.md) the same through b, a collision on the beam, but no
  // mollified one (an own vertex's elastic merge through the kernel has no beam); v a photon point or
  // a point of a photon beam.
  const bool beam = along.kind != Along::Kind::Point, photon = along.kind == Along::Kind::PhotonBeam;
  Kind kinds[2];
  int n = 0;
  if (!own && withinRadius)
    kinds[n++] = {SpectralLobe::Elastic, photon ? Variant::kPhotonBeam : beam ? Variant::kBeam : Variant::kMerge};
  if (own && (withinRadius || gather) && b.bsdf->has(BsdfFlags::Fluorescent))
    kinds[n++] = {SpectralLobe::Fluorescent, photon ? Variant::kPhotonBeamOwn : beam ? Variant::kBeamOwn : Variant::kMergeOwn};
  if (!beam && own && withinRadius && c.bandwidth > 0.0f && std::abs(v.lambda - lambdaB) < c.bandwidth)
    kinds[n++] = {SpectralLobe::Elastic, Variant::kMergeMollified};
  const Bsdf& fb = *b.bsdf;
  const Vec3 bWi(v.wi[0], v.wi[1], v.wi[2]), bWo = fb.toLocal(towards(b, bNext));
  const int m = v.depth;
  for (int i = 0; i < n; ++i) {
    const SpectralLobe lobe = kinds[i].lobe;
    const Variant variant = kinds[i].variant;
    const double etaMerge = etaOf(c.walk.strategies.merge, variant, gather, b.inMedium());
    // A photon beam's estimate: the chord over N·π r_v², which is η_pb·2r_v (MergeEta::photonBeam).
    const double norm = photon ? etaMerge * 2.0 * c.walk.strategies.merge.volumeRadius : etaMerge;
    const float scale = fb.incidentShadingRatio(bWi) * laneFactor * along.chord / float(norm);
    // The wavelengths of the densities at x_m: the light arriving and the camera's leaving, the
    // same through the elastic lobe (the camera's, one that scatters there, §10).
    const float lambdaOut = lambdaB;
    const bool ownPart = variant == Variant::kMergeOwn || isOwnBeam(variant);
    const float lambdaIn = ownPart ? v.lambda : lambdaOut;
    // Mollified: δ(λ_v − λ_b) widened to K_h, renormalised inside the range (docs/bdpt-mis.md eq. 5).
    const WavelengthRange& r = c.scene.range;
    const float kernel = variant == Variant::kMergeMollified
                             ? wavelengthKernel(v.lambda - lambdaB, c.bandwidth) /
                                   wavelengthKernelMass(r.min - lambdaB, r.max - lambdaB, c.bandwidth)
                             : 1.0f;
    float value[kMaxLanes];
    bool any = false;
    for (int k = k0; k < k1; ++k) {
      const float lambda = b.lanesEndHere || b.allLanes(c.lanes) ? c.lanes.lambda[k] : lambdaB;
      const float f = own ? fb.eval({TransportMode::Radiance, lobe, lambdaIn, lambdaOut}, bWi, bWo)
                          : fb.eval({TransportMode::Radiance, lobe, lambda, lambda}, bWi, bWo);
      value[k] = betaB[k] * f * v.beta[own ? 0 : k] * scale * kernel;
      any = any || value[k] > 0.0f;
    }
    if (!any) continue;
    const MergeSums sums = mergeSums(c, C, t, v, lobe, lambdaIn, lambdaOut, gather, bWi, bWo);
    // This merge: (η·pC_m)² relative to the strategy s' = m + 1; a beam's (η_b·pC_m·ρ_C)² (eq. B2), a
    // photon beam's (η_pb·pC_m·ρ_C·ρ_L·sin θ)² (eq. B4).
    const double eta =
        etaMerge * b.pdfFwd * (beam ? double(b.cameraBeam) : 1.0) * (photon ? photonBeamRatio(lightBeamOf(c, v, b), sums.beamSine) : 1.0);
    MisSums mine;
    const bool sharedPart = variant == Variant::kMerge || (isBeam(variant) && !isOwnBeam(variant));
    (sharedPart ? mine.mergeShared : ownPart ? mine.mergeOwn : mine.mergeMollified) = eta * eta;
    const bool single = oneGroup(v, b, lobe);
    const bool lanesKept = v.has(LightVertex::kLanesKept) && b.lanesKept;
    float weight[kMaxLanes];
    laneWeights(c, k0, k1, weight, [&](int k) { return value[k] > 0.0f; }, [&](int k) {
      const float lambda0 = own ? v.lambda0 : v.lane < 0 && c.lanes.n > 1 ? c.lanes.lambda[k] : v.lambda;
      const MisFactors f = own ? factors(c, v.light, lambda0, -1, c.lanes.pdf[k], single, lanesKept,
                                         c.walk.lightFirst ? v.ownStart : 0.0f)
                               : factors(c, v.light, lambda0, k, c.lanes.pdf[k], single, lanesKept);
      return weigh(c, m, t, variant, mine, sums.total, f, [&](const MisFactors& g) {
        return fullPath(c, C, t, v, lightPath, lobe, sums, g, along);
      });
    });
    for (int k = k0; k < k1; ++k) {
      if (!(value[k] > 0.0f)) continue;
      record(c, m, t, variant, k, value[k], weight[k]);
      out[k] += value[k] * weight[k];
    }
  }
}

// Merges own vertex v with b = C[1], the camera ray's hit, through b's elastic lobe at v's own
// wavelength, where the sensor responds (Variant::kMergeSplat, docs/bdpt-mis.md §12); betaB b's
// throughput, which does not depend on λ. Appends the weighted radiance at v.lambda to `atLight`.
void mergeSplat(const Context& c, const std::vector<PathVertex>& C, const LightVertex& v, float betaB,
                std::vector<SpectralSample>& atLight, const std::vector<PathVertex>* lightPath) {
  const PathVertex& b = C[1];
  const Bsdf& fb = *b.bsdf;
  const Vec3 bWi(v.wi[0], v.wi[1], v.wi[2]), bWo = fb.toLocal(towards(b, C[0]));
  const SpectralLobe lobe = SpectralLobe::Elastic;
  const float lambda = v.lambda;
  const double etaMerge = etaOf(c.walk.strategies.merge, Variant::kMergeSplat, true, b.inMedium());
  const float value = betaB * fb.eval({TransportMode::Radiance, lobe, lambda, lambda}, bWi, bWo) * v.beta[0] *
                      fb.incidentShadingRatio(bWi) / float(etaMerge);
  if (!(value > 0.0f)) return;
  const MergeSums sums = mergeSums(c, C, 2, v, lobe, lambda, lambda, true, bWi, bWo);
  const double eta = etaMerge * b.pdfFwd;
  MisSums mine;
  mine.mergeOwnSplat = eta * eta;
  const MisFactors f = factors(c, v.light, v.lambda0, -1, c.sensor.pdf(lambda), oneGroup(v, b, lobe),
                               v.has(LightVertex::kLanesKept) && b.lanesKept, c.walk.lightFirst ? v.ownStart : 0.0f);
  const float weight = weigh(c, v.depth, 2, Variant::kMergeSplat, mine, sums.total, f, [&](const MisFactors& g) {
    return fullPath(c, C, 2, v, lightPath, lobe, sums, g, Along{});
  });
  if (!(weight > 0.0f)) return;
  if (c.observer) {  // in lane 0's slot, which takes the weight just computed
    c.observer->onLaneKept(0);
    recordXyz(c, v.depth, 2, Variant::kMergeSplat, 0, Observer::cie1931().weight(lambda) * value, weight);
  }
  atLight.push_back({lambda, value * weight});
}

// merge's, and along a query beam mergeBeam's and mergePhotonBeam's (C[t − 1] then a collision on it).
void mergeAt(const Context& c, const std::vector<PathVertex>& C, int t, const LightVertex& v, bool withinRadius,
             const Along& along, float* out, std::vector<SpectralSample>& atLight,
             const std::vector<PathVertex>* lightPath) {
  const bool beam = along.kind != Along::Kind::Point;
  const PathVertex& b = C[size_t(t - 1)];
  // A collision in a medium merges within the volume radius alone (η_v for every variant, MergeEta):
  // no wider gather there.
  const bool gather = b.gather && !b.inMedium();
  const bool own = v.has(LightVertex::kOwn);
  if (!mergeable(b, true) || (!withinRadius && !(gather && own))) return;
  // b's lanes as the light arriving there sees them: where b ended the lanes on arrival, every lane
  // that arrived (the merge evaluates b's event itself, docs/bdpt-mis.md §12).
  const bool ended = b.lanesEndHere;
  const float* beta = ended ? b.betaArriving : b.beta;
  const int bLane = ended ? -1 : b.lane;
  if (!beam && own && t == 2 && etaOf(c.walk.strategies.merge, Variant::kMergeSplat, true, b.inMedium()) > 0.0)
    mergeSplat(c, C, v, beta[0], atLight, lightPath);
  // The lanes served: on a shared vertex (it carries the camera sample's lanes) those both reach; on
  // an own one every lane that reaches b, each a merge of its own (an own join keeps one of them at
  // random, ownJoinLane: the merge sums them all, that choice's expectation).
  const int k0 = std::max(own || v.lane < 0 ? 0 : int(v.lane), bLane < 0 ? 0 : bLane);
  const int k1 = std::min(own || v.lane < 0 ? c.lanes.n : v.lane + 1, bLane < 0 ? c.lanes.n : bLane + 1);
  const float laneFactor = own ? 1.0f : keptLaneScale(c, v.lane, bLane);
  // Where several lanes reach b and its densities depend on λ (own merges; b that ended them), each
  // lane's densities at its own wavelength.
  if (k1 - k0 > 1 && (own || ended)) {
    for (int k = k0; k < k1; ++k)
      if (beta[k] > 0.0f)
        mergeLanes(c, C, t, v, withinRadius, along, gather, k, k + 1, c.lanes.lambda[k], beta, laneFactor, out, lightPath);
  } else if (k0 < k1) {
    const float lambdaB = ended ? c.lanes.lambda[k0] : b.lambda;
    mergeLanes(c, C, t, v, withinRadius, along, gather, k0, k1, lambdaB, beta, laneFactor, out, lightPath);
  }
}

// The collision at distance `along` on the query beam q of C[t−2] → C[t−1] = e, as the camera side's
// free flight would have made it (its densities, sums and lanes are a collision's there), with the
// throughput of the beam: the flight's weight T/p that e took replaced by T/R_C (eq. B3).
PathVertex beamVertex(const Context& c, const std::vector<PathVertex>& C, int t, const PathVertex& e,
                      const QueryBeam& q, float along) {
  const Scene& scene = c.scene;
  const PathVertex& y = C[size_t(t - 2)];
  PathVertex b;
  b.kind = Kind::Medium;
  b.p = q.origin + along * q.w;
  b.bsdf = scene.mediumBsdf(q.medium, b.p);
  b.medium = q.medium;
  const float lambda = e.lambda;
  b.arrival = depthThrough(scene, q.medium, lambda, along);
  b.lane = e.lane;
  b.lambda = lambda;
  b.elasticBefore = e.elasticBefore;
  b.lanesKept = false;
  b.gather = e.gather;
  b.sums = e.sums;  // updateSums: from C[t−2] and C[t−3] alone
  const double reach = freeFlightDensity(scene.hasFluorescentMedia(), b.arrival, 1.0f, 1.0f);  // R_C
  b.cameraBeam = float(cameraBeamRatio(scene, b.arrival, b, lambda));                         // R_C/F_C
  b.pdfFwd = float(q.directionPdf * toAreaDensity(1.0f, y, b) *
                   flightFactor(scene, TransportMode::Radiance, b.arrival, b, lambda));
  const float scale = float(std::exp(-double(b.arrival.analog)) / reach) / e.flightWeight;
  for (int k = 0; k < c.lanes.n; ++k) b.beta[k] = e.beta[k] * scale;
  return b;
}

}  // namespace

void merge(const Context& c, const std::vector<PathVertex>& C, int t, const LightVertex& v, bool withinRadius,
           float* out, std::vector<SpectralSample>& atLight, const std::vector<PathVertex>* lightPath) {
  mergeAt(c, C, t, v, withinRadius, Along{}, out, atLight, lightPath);
}

std::optional<QueryBeam> queryBeam(const Context& c, const std::vector<PathVertex>& C, int t) {
  const Scene& scene = c.scene;
  const PathVertex& y = C[size_t(t - 2)];
  const PathVertex& e = C[size_t(t - 1)];
  const MergeEta& eta = c.walk.strategies.merge;
  if (!(eta.beam > 0.0 || eta.photonBeam > 0.0) || !e.arrival.inMedia || !(e.flightWeight > 0.0f)) return std::nullopt;
  QueryBeam q;
  q.origin = y.p;
  const Vec3 towardsE = e.kind == Kind::Infinite ? -e.dir : e.p - y.p;
  const float norm = glm::length(towardsE);
  if (!(norm > 0.0f) || !std::isfinite(norm)) return std::nullopt;  // a segment of no length has no beam
  q.w = towardsE / norm;
  q.medium = mediumToward(scene, y, q.w);
  if (q.medium < 0 || scene.media[size_t(q.medium)]->heterogeneous()) return std::nullopt;
  // C[t−2]'s density of the direction, from e's area density (pdfSA·G·F).
  q.directionPdf = e.pdfFwd / (double(toAreaDensity(1.0f, y, e)) *
                               flightFactor(scene, TransportMode::Radiance, e.arrival, e, e.lambda));
  if (!(q.directionPdf > 0.0) || !std::isfinite(q.directionPdf)) return std::nullopt;
  if (!e.arrival.crossesBoundary) {
    q.length = e.kind == Kind::Infinite ? kInf : norm;
  } else {  // up to the first boundary
    ++c.counter.closest;
    const std::optional<Hit> hit = scene.accel->intersect(Ray{offsetPoint(y.p, y.n, q.w), q.w});
    if (!hit) return std::nullopt;
    q.length = glm::length(hit->p - y.p);
  }
  return q;
}

namespace {

// Merges v (a photon point, or a point of a photon beam) with a collision at distance `along` on the
// query beam q of C[t−1] (mergeBeam, mergePhotonBeam).
void mergeAlong(const Context& c, std::vector<PathVertex>& C, int t, const QueryBeam& q, float at, const LightVertex& v,
                const Along& along, float* out, const std::vector<PathVertex>* lightPath) {
  PathVertex e = std::move(C[size_t(t - 1)]);
  C[size_t(t - 1)] = beamVertex(c, C, t, e, q, at);
  // C[t−2]'s light-side beam ratio over the shorter segment, which crosses no boundary.
  PathVertex& y = C[size_t(t - 2)];
  const float yBeam = y.lightBeam;
  if (c.walk.strategies.merge.photonBeam > 0.0) {
    const PathVertex& b = C[size_t(t - 1)];
    y.lightBeam = float(lightBeamRatio(c.scene, b.arrival, y, b, b.lambda));
  }
  std::vector<SpectralSample> none;  // a beam has no merge at the light vertex's own wavelength
  mergeAt(c, C, t, v, true, along, out, none, lightPath);
  y.lightBeam = yBeam;
  C[size_t(t - 1)] = std::move(e);
}

}  // namespace

void mergeBeam(const Context& c, std::vector<PathVertex>& C, int t, const QueryBeam& q, float along, const LightVertex& v,
               float* out, const std::vector<PathVertex>* lightPath) {
  mergeAlong(c, C, t, q, along, v, Along{Along::Kind::QueryBeam}, out, lightPath);
}

void mergePhotonBeam(const Context& c, std::vector<PathVertex>& C, int t, const QueryBeam& q, const PhotonBeam& beam,
                     const BeamCrossing& x, float* out, const std::vector<PathVertex>* lightPath) {
  // The light side's densities of the merged vertex from its distance to the beam's origin: the
  // camera side's point's, as every other strategy of the path sees it, not its projection onto the
  // beam, which is nearer and would weigh the beam up wherever it passes close by its origin.
  const Vec3 at = q.origin + x.t * q.w;
  // As at every collision (docs/media.md §6), no merge where the merged vertex's sphere meets a surface:
  // there the path's other strategies have none either.
  if (!sphereClearOfSurfaces(c.scene, at, float(c.walk.strategies.merge.volumeRadius), c.counter)) return;
  const float s = glm::length(at - beam.origin);
  const BeamPoint point = vertexAlong(c.scene, beam, s);
  mergeAlong(c, C, t, q, x.t, point.vertex, Along{Along::Kind::PhotonBeam, x.chord, point.originCameraBeam}, out,
             lightPath);
}

std::optional<BeamCrossing> crossing(const QueryBeam& q, const PhotonBeam& beam, float radius, float u) {
  // The closest points of the query line o + t·c and the beam line a + s·w, at distance g.
  const Vec3 w0 = q.origin - beam.origin;
  const float cw = glm::dot(q.w, beam.w), sin2 = 1.0f - cw * cw;
  if (!(sin2 > 1e-8f)) return std::nullopt;  // parallel: no crossing point
  const float dw = glm::dot(w0, beam.w), dc = glm::dot(w0, q.w);
  const float tClosest = (cw * dw - dc) / sin2, sClosest = (dw - cw * dc) / sin2;
  const Vec3 gap = (q.origin + tClosest * q.w) - (beam.origin + sClosest * beam.w);
  const float g2 = glm::dot(gap, gap);
  if (!(g2 < radius * radius)) return std::nullopt;
  // The query points inside the cylinder: within r of the beam's line, t* ± √(r² − g²)/sin θ, inside
  // the query, and projecting into the beam, s(t) = s* + (t − t*)·cos θ in [0, length].
  const float half = std::sqrt((radius * radius - g2) / sin2);
  float lo = std::max(tClosest - half, 0.0f), hi = std::min(tClosest + half, q.length);
  if (std::abs(cw) > 0.0f) {
    const float a = tClosest - sClosest / cw, b = tClosest + (beam.length - sClosest) / cw;
    lo = std::max(lo, std::min(a, b)), hi = std::min(hi, std::max(a, b));
  } else if (!(sClosest >= 0.0f && sClosest <= beam.length)) {
    return std::nullopt;
  }
  if (!(hi > lo)) return std::nullopt;
  BeamCrossing x;
  x.chord = hi - lo;
  x.t = lo + u * x.chord;
  x.s = sClosest + (x.t - tClosest) * cw;
  if (!(x.t > 0.0f && x.s > 0.0f && x.s <= beam.length)) return std::nullopt;
  return x;
}

}  // namespace kasha::bidir
