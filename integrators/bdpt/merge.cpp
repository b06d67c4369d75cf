#include "integrators/bdpt/merge.h"

#include <algorithm>

#include "integrators/bdpt/connect_parts.h"
#include "integrators/progressive_schedule.h"

namespace kasha::bdpt {

namespace {

// Merges v with b = C[t−1] at lanes [k0, k1) (docs/bdpt-mis.md §12; `gather`: b is the path's first
// gather vertex, merge.h for withinRadius): lambdaB the wavelength of b's densities (and of an own
// vertex's one lane), betaB b's throughput per lane, times laneFactor.
void mergeLanes(const Context& c, const std::vector<PathVertex>& C, int t, const LightVertex& v, bool withinRadius,
                bool gather, int k0, int k1, float lambdaB, const float* betaB, float laneFactor, float* out,
                const std::vector<PathVertex>* lightPath) {
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
  Kind kinds[2];
  int n = 0;
  if (!own && withinRadius) kinds[n++] = {SpectralLobe::Elastic, Variant::kMerge};
  if (own && (withinRadius || gather) && b.bsdf->has(BsdfFlags::Fluorescent))
    kinds[n++] = {SpectralLobe::Fluorescent, Variant::kMergeOwn};
  if (own && withinRadius && c.bandwidth > 0.0f && std::abs(v.lambda - lambdaB) < c.bandwidth)
    kinds[n++] = {SpectralLobe::Elastic, Variant::kMergeMollified};
  const Bsdf& fb = *b.bsdf;
  const Vec3 bWi(v.wi[0], v.wi[1], v.wi[2]), bWo = fb.toLocal(towards(b, bNext));
  const Strategies& st = c.walk.strategies;
  const int m = v.depth;
  for (int i = 0; i < n; ++i) {
    const SpectralLobe lobe = kinds[i].lobe;
    const Variant variant = kinds[i].variant;
    const double etaMerge = etaOf(st.merge, variant, gather);
    const float scale = fb.incidentShadingRatio(bWi) * laneFactor / float(etaMerge);
    // The wavelengths of the densities at x_m: the light arriving and the camera's leaving, the
    // same through the elastic lobe (the camera's, one that scatters there, §10).
    const float lambdaOut = lambdaB;
    const float lambdaIn = variant == Variant::kMergeOwn ? v.lambda : lambdaOut;
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
      const float f = own ? fb.eval(TransportMode::Radiance, bWi, bWo, lambdaIn, lambdaOut, lobe)
                          : fb.eval(TransportMode::Radiance, bWi, bWo, lambda, lambda, lobe);
      value[k] = betaB[k] * f * v.beta[own ? 0 : k] * scale * kernel;
      any = any || value[k] > 0.0f;
    }
    if (!any) continue;
    // The densities next to the merge: the camera side's of x_{m−1}, sampled at x_m, and the light
    // side's of x_{m+1}; the merge's own vertex keeps both sides' stored densities.
    const double specCam = fb.spectralPdf(TransportMode::Radiance, lambdaOut, lambdaIn, lobe);
    const double specLight = fb.spectralPdf(TransportMode::Importance, lambdaIn, lambdaOut, lobe);
    const double pCamPrev =
        specCam * fb.directionPdf(TransportMode::Radiance, bWo, bWi, lobe, lambdaIn, lambdaOut) * v.prevGeometry;
    // The light side (eq. 10 from the sum the light vertex kept): the strategy s' = m, whose
    // connection ends at x_m, with the merges at x_m.
    const SpectralLobe prevLobe =
        v.has(LightVertex::kPrevFluorescent) ? SpectralLobe::Fluorescent : SpectralLobe::Elastic;
    const MisSums mLast = mergeMultiplicity(true, lobe, v.pdfFwd, gather, st) +
                          (m == 1 ? firstVertexMultiplicity(true, lobe, specCam, v.has(LightVertex::kFiniteLight), st)
                                  : joinMultiplicity(v.has(LightVertex::kPrevConnectible), prevLobe, lobe, st));
    const double rPrev = densityRatio(pCamPrev, v.pdfPrev);
    MisSums total = extend(v.sums * (rPrev * rPrev), densityRatio(b.pdfFwd, v.pdfFwd), mLast);
    // The strategy s' = m + 1 (x_m the last light vertex), and the camera side beyond it.
    double pLightNext = 0.0;
    if (t == 2) {
      total = total + lightTracingMultiplicity(true, specLight, st);
    } else {
      const double pdf = specLight * fb.directionPdf(TransportMode::Importance, bWi, bWo, lobe, lambdaIn, lambdaOut);
      pLightNext = toArea(c.scene, float(pdf), b, bNext);
      total = total + joinMultiplicity(bNext.connectible(), lobe, bNext.lobe, st) +
              cameraSum(c, C, t - 1, pLightNext, cameraMultiplicity(C, t - 2, st), C[size_t(t - 3)].pdfRev);
    }
    // This merge: (η·pC_m)² relative to the strategy s' = m + 1.
    const double eta = etaMerge * b.pdfFwd;
    MisSums mine;
    (variant == Variant::kMerge ? mine.shared : variant == Variant::kMergeOwn ? mine.own : mine.mollified) = eta * eta;
    // Whether the path has one group: a property of the path, whichever family made it.
    const bool oneGroup = lobe == SpectralLobe::Elastic && v.has(LightVertex::kElasticBefore) && b.elasticBefore;
    const bool lanesKept = v.has(LightVertex::kLanesKept) && b.lanesKept;
    float weight[kMaxLanes];
    laneWeights(c, k0, k1, weight, [&](int k) { return value[k] > 0.0f; }, [&](int k) {
      const float lambda0 = own ? v.lambda0 : v.lane < 0 && c.lanes.n > 1 ? c.lanes.lambda[k] : v.lambda;
      const MisFactors f = own ? factors(c, v.light, lambda0, -1, c.lanes.sensorPdf[k], oneGroup, lanesKept,
                                         c.walk.lightFirst ? v.ownStart : 0.0f)
                               : factors(c, v.light, lambda0, k, c.lanes.sensorPdf[k], oneGroup, lanesKept);
      return weigh(c, m, t, variant, mine, total, f, [&](const MisFactors& g) {
        const std::vector<PathVertex>& L = *lightPath;
        FullPath fp = layout(c, &L, m + 1, C, t - 1, storedLightEnd(L, m + 1), g);
        fp.v[size_t(m)].lobe = lobe;
        fp.v[size_t(m)].pdfCam = b.pdfFwd;
        fp.v[size_t(m - 1)].pdfCam = pCamPrev;
        if (t > 2) fp.v[size_t(m + 1)].pdfLight = pLightNext;
        fp.specCam1 = m == 1 ? specCam : specCamera(L[1], L[1].lobe, L[1].lambda, L[1].lambdaNext);
        fp.specLightLast = t == 2 ? specLight : specLightLast(C[1], C[1].lobe, C[1].lambdaNext);
        return misWeight(fp, m, variant);
      });
    });
    for (int k = k0; k < k1; ++k) {
      if (!(value[k] > 0.0f)) continue;
      record(c, m, t, variant, k, value[k], weight[k]);
      out[k] += value[k] * weight[k];
    }
  }
}

}  // namespace

void merge(const Context& c, const std::vector<PathVertex>& C, int t, const LightVertex& v, bool withinRadius,
           float* out, const std::vector<PathVertex>* lightPath) {
  const PathVertex& b = C[size_t(t - 1)];
  const bool gather = b.gather;
  if (!mergeable(b) || (!withinRadius && !(gather && v.has(LightVertex::kOwn)))) return;
  // b's lanes as the light arriving there sees them: where b ended the lanes on arrival, every lane
  // that arrived (the merge evaluates b's event itself, docs/bdpt-mis.md §12).
  const bool ended = b.lanesEndHere;
  const float* beta = ended ? b.betaArriving : b.beta;
  const int bLane = ended ? -1 : b.lane;
  const bool own = v.has(LightVertex::kOwn);
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
        mergeLanes(c, C, t, v, withinRadius, gather, k, k + 1, c.lanes.lambda[k], beta, laneFactor, out, lightPath);
  } else if (k0 < k1) {
    const float lambdaB = ended ? c.lanes.lambda[k0] : b.lambda;
    mergeLanes(c, C, t, v, withinRadius, gather, k0, k1, lambdaB, beta, laneFactor, out, lightPath);
  }
}

}  // namespace kasha::bdpt
