#include "integrators/bidirectional/connect.h"

#include <algorithm>

#include "core/color.h"
#include "integrators/bidirectional/connect_parts.h"
#include "integrators/bidirectional/path_media.h"
#include "integrators/progressive_schedule.h"

namespace kasha::bidir {

void emitterHit(const Context& c, const std::vector<PathVertex>& C, int t, float* out, Vec3& xyz) {
  const PathVertex& e = C[size_t(t - 1)];
  if (e.light < 0) return;
  const PathVertex& next = C[size_t(t - 2)];
  if (t == 2 && e.kind == Kind::Surface && c.directXyz) {
    // The path x_0 x_1 (the light seen by the pinhole) has two strategies, this one and the light
    // vertex splatted to the camera; this one is exact, so it takes weight 1 and the other 0
    // (docs/bdpt-mis.md §10).
    const AreaEmission& em = *static_cast<const AreaLight&>(*c.scene.lights[size_t(e.light)]).shape().emission;
    if (!em.emitsTowards(e.n, towards(e, next))) return;
    const Vec3& value = (*c.directXyz)[size_t(e.light)];
    xyz += value;
    if (c.observer) c.observer->onStrategy({c.pixel, value, value, 0, t, uint8_t(Variant::kStandard)});
    return;
  }
  float Le[kMaxLanes];
  bool any = false;
  for (int k = e.firstLane(); k < e.endLane(c.lanes); ++k) {
    Le[k] = emitted(c, e, next, e.lambdaOf(c.lanes, k));
    any = any || Le[k] > 0.0f;
  }
  if (!any) return;
  const LightEnd end = lightEnd(c, e.light, e, next, e.arrival, e.lambda);
  const int k = t - 1;
  // The strategies with one light vertex: next-event estimation and the light vertex at x_1, or
  // for k = 1 the light seen by the camera.
  const Strategies& st = c.walk.strategies;
  const MisSums m1 = k >= 2 ? firstVertexMultiplicity(next.joinable(false), next.lobe, next.spectralPdf, end.finite, st)
                            : directLightMultiplicity(e.kind == Kind::Surface, st);
  const MisSums own = hitMultiplicity();
  const MisSums total = own + cameraSum(c, C, t, end.pdf0, m1, end.pdf1);
  float weight[kMaxLanes];
  laneWeights(c, e.firstLane(), e.endLane(c.lanes), weight, [&](int j) { return Le[j] > 0.0f; }, [&](int j) {
    const MisFactors f = factors(c, e.light, e.lambdaOf(c.lanes, j), e.elasticBefore ? j : -1, c.lanes.pdf[j],
                                 e.elasticBefore, next.lanesKept);
    return weigh(c, 0, t, Variant::kStandard, own, total, f, [&](const MisFactors& g) {
      FullPath fp = layout(c, nullptr, 0, C, t, end, g, true);
      if (k >= 2) {
        fp.specCam1 = next.spectralPdf;
        fp.specLightLast = specLightLast(C[1], C[1].lobe, C[1].lambdaNext);
      } else {
        fp.lightSeenByPinhole = e.kind == Kind::Surface;
      }
      return fp;
    });
  });
  for (int j = e.firstLane(); j < e.endLane(c.lanes); ++j) {
    const float value = e.beta[j] * Le[j];
    record(c, 0, t, Variant::kStandard, j, value, weight[j]);
    out[j] += value * weight[j];
  }
}

void nextEvent(const Context& c, const std::vector<PathVertex>& C, int t, Sampler& rng, float* out) {
  const PathVertex& x1 = C[size_t(t - 1)];
  const float uSel = rng.uniform();
  const Vec2 uPos = rng.uniform2();
  if (!x1.eventSampled || !x1.connectible()) return;
  const float lambda0 = x1.lambdaNext;
  // On a path that has not fluoresced the light is chosen for the lanes, as light subpaths choose it.
  const bool cameraGroup = x1.elasticBefore && x1.lobe == SpectralLobe::Elastic;
  const auto [li, pSel] = cameraGroup ? selectLight(c.scene, c.lanes, uSel) : c.scene.lightSelector->select(lambda0, uSel);
  if (pSel <= 0.0f) return;
  const Light& light = *c.scene.lights[li];
  const std::optional<LightSample> ls = light.sampleLi(x1.p, lambda0, uPos);
  if (!ls || ls->pdf <= 0.0f) return;
  // The light vertex x_0.
  PathVertex x0;
  x0.kind = light.atInfinity() ? Kind::Infinite : Kind::Light;
  x0.light = int(li);
  x0.lambda = lambda0;
  x0.deltaPosition = light.isDelta() && !light.atInfinity();
  if (light.atInfinity()) {
    x0.dir = -ls->wi;
  } else {
    x0.p = x1.p + ls->wi * ls->dist;
    x0.n = ls->n;
  }
  const Bsdf& f = *x1.bsdf;
  const PathVertex& x2 = C[size_t(t - 2)];
  const Vec3 wi = f.toLocal(ls->wi), wo = f.toLocal(towards(x1, x2));
  // Each lane through x_1's event: elastic at the lane's own wavelength when every lane reaches x_1.
  float value[kMaxLanes];
  bool any = false;
  const bool lanes = x1.allLanes(c.lanes);
  for (int k = x1.firstLane(); k < x1.endLane(c.lanes); ++k) {
    const float lambda = lanes ? c.lanes.lambda[k] : lambda0;
    const float fx = lanes ? x1.bsdf->eval({TransportMode::Radiance, x1.lobe, lambda, lambda}, wi, wo)
                           : x1.bsdf->eval({TransportMode::Radiance, x1.lobe, lambda0, x1.lambda}, wi, wo);
    // The light's geometry does not depend on λ: the same point at every lane's wavelength.
    const float Li = lanes ? light.Li(*ls, lambda) : ls->Li;
    value[k] = fx > 0.0f ? x1.beta[k] * fx * f.cosineFactor(wi) / x1.spectralPdf * Li / (pSel * ls->pdf) : 0.0f;
    any = any || value[k] > 0.0f;
  }
  // Through the media from x_1 to x_0, at λ_0; where several lanes reach x_1, at lane 0's
  // wavelength, and a segment through a medium serves lane 0 alone (laneZeroThroughMedia).
  SegmentDepth toLight;
  if (!any || !visible(c, x1, x0, lanes && c.scene.hasMedia() ? c.lanes.lambda[0] : lambda0, &toLight)) return;
  const bool laneZero = lanes && toLight.inMedia;
  if (laneZero) laneZeroThroughMedia(c, value);
  // The wavelengths of the densities: λ_0 and x_1's own, or lane 0's alone.
  const float lambdaIn = laneZero ? c.lanes.lambda[0] : lambda0, lambdaX1 = laneZero ? lambdaIn : x1.lambda;
  x0.lambda = lambdaIn;
  for (int k = x1.firstLane(); k < x1.endLane(c.lanes); ++k) value[k] *= transmittance(toLight);
  const int lightIndex = int(li);  // a structured binding cannot be captured (clang 14)
  const LightEnd end = lightEnd(c, lightIndex, x0, x1, toLight, lambdaIn);
  const double pCam0 =
      densityToward(c.scene, {TransportMode::Radiance, x1.lobe, lambdaIn, lambdaX1}, x1, wo, wi, x0, toLight);
  const double pLight2 =
      x2.kind != Kind::Camera
          ? densityToward(c.scene, {TransportMode::Importance, x1.lobe, lambdaIn, lambdaX1}, x1, wi, wo, x2, x1.arrival)
          : 0.0;
  const MisSums m1 = firstVertexMultiplicity(true, x1.lobe, x1.spectralPdf, end.finite, c.walk.strategies);
  MisSums own;
  own.nee = x1.spectralPdf * double(x1.spectralPdf);
  const double beamX1 =
      c.walk.strategies.merge.photonBeam > 0.0 ? lightBeamRatio(c.scene, toLight, x1, x0, lambdaIn) : 0.0;
  const double sineX1 = beamX1 > 0.0 ? crossingSine(x1.p, x0.p, x2.p) : 0.0;
  const MisSums total =
      m1 + lightEndSum(pCam0, end.pdf0) +
      cameraSum(c, C, t, end.pdf1,
                cameraMultiplicity(C, t - 1, x1.lobe, x1.lambdaNext, c.walk.strategies, true, beamX1, sineX1), pLight2);
  float weight[kMaxLanes];
  laneWeights(c, x1.firstLane(), x1.endLane(c.lanes), weight, [&](int k) { return value[k] > 0.0f; }, [&](int k) {
    const MisFactors f = factors(c, lightIndex, lanes ? c.lanes.lambda[k] : lambda0, cameraGroup ? k : -1,
                                 c.lanes.pdf[k], cameraGroup, x1.lanesKept);
    return weigh(c, 1, t, Variant::kStandard, own, total, f, [&](const MisFactors& g) {
      PathVertex lightVertex = x0;
      lightVertex.pdfFwd = float(end.pdf0);
      lightVertex.pdfRev = float(pCam0);
      const std::vector<PathVertex> L1{lightVertex};
      FullPath fp = layout(c, &L1, 1, C, t, end, g, true);
      if (x2.kind != Kind::Camera) fp.v[2].pdfLight = pLight2;
      fp.v[1].lightBeam = beamX1;
      fp.v[1].beamSine = sineX1;
      fp.specCam1 = x1.spectralPdf;
      fp.specLightLast = specLightLast(C[1], C[1].lobe, C[1].lambdaNext);
      return fp;
    });
  });
  for (int k = x1.firstLane(); k < x1.endLane(c.lanes); ++k) {
    if (!(value[k] > 0.0f)) continue;
    record(c, 1, t, Variant::kStandard, k, value[k], weight[k]);
    out[k] += value[k] * weight[k];
  }
}

// x_1 = b is fluorescent, so one lane reaches it (docs/bdpt-mis.md §10).
void connectLightVertex(const Context& c, const std::vector<PathVertex>& L, const std::vector<PathVertex>& C, int t,
                        float* out) {
  const PathVertex& a = L[0];
  const PathVertex& b = C[size_t(t - 1)];
  if (a.kind != Kind::Light || !b.scatters() || !b.connectible() || !b.bsdf->has(BsdfFlags::Fluorescent)) return;
  const PathVertex& bNext = C[size_t(t - 2)];
  const Vec3 d = b.p - a.p;
  const float dist2 = glm::dot(d, d);
  if (!(dist2 > 0.0f)) return;
  const Vec3 w = d / std::sqrt(dist2);
  const float Le = c.scene.lights[size_t(a.light)]->emittedTowards(a.lambda, a.n, w);
  if (!(Le > 0.0f)) return;
  const Bsdf& fb = *b.bsdf;
  const Vec3 bWi = fb.toLocal(-w), bWo = fb.toLocal(towards(b, bNext));
  // x_1 bridges the light's wavelength to the camera's with its fluorescent lobe.
  constexpr SpectralLobe F = SpectralLobe::Fluorescent;
  const float f = b.bsdf->eval({TransportMode::Radiance, F, a.lambda, b.lambda}, bWi, bWo);
  if (!(f > 0.0f)) return;
  // In a scene with media the segment is traced first: its densities need its optical depths.
  const bool media = c.scene.hasMedia();
  SegmentDepth segment;
  if (media && !visible(c, b, a, a.lambda, &segment)) return;
  const int lane = b.firstLane();
  const float G = a.cosine(w) * fb.cosineFactor(bWi) / dist2;
  const LightEnd end = lightEnd(c, a.light, a, b, segment, a.lambda);
  const double pCam0 =
      densityToward(c.scene, {TransportMode::Radiance, F, a.lambda, b.lambda}, b, bWo, bWi, a, segment);
  const double pLight2 =
      bNext.kind != Kind::Camera
          ? densityToward(c.scene, {TransportMode::Importance, F, a.lambda, b.lambda}, b, bWi, bWo, bNext, b.arrival)
          : 0.0;
  const double specCam1 = specCamera(b, F, a.lambda, b.lambda);
  MisSums own;
  own.own = 1.0;
  const Strategies& st = c.walk.strategies;
  const double beamB = st.merge.photonBeam > 0.0 ? lightBeamRatio(c.scene, segment, b, a, a.lambda) : 0.0;
  const double sineB = beamB > 0.0 ? crossingSine(b.p, a.p, bNext.p) : 0.0;
  const MisSums total = firstVertexMultiplicity(true, F, specCam1, true, st) + lightEndSum(pCam0, a.pdfFwd) +
                        cameraSum(c, C, t, end.pdf1, cameraMultiplicity(C, t - 1, F, a.lambda, st, true, beamB, sineB),
                                  pLight2);
  const MisFactors mf = factors(c, a.light, a.lambda, -1, c.lanes.pdf[lane], false, false,
                                c.walk.lightFirst ? a.choicePdf : 0.0f);
  const float weight = weigh(c, 1, t, Variant::kLightVertex, own, total, mf, [&](const MisFactors& g) {
    FullPath fp = layout(c, &L, 1, C, t, end, g, true);
    fp.v[1].lobe = F;
    fp.v[0].pdfCam = pCam0;
    fp.v[1].lightBeam = beamB;
    fp.v[1].beamSine = sineB;
    if (bNext.kind != Kind::Camera) fp.v[2].pdfLight = pLight2;
    fp.specCam1 = specCam1;
    fp.specLightLast = t == 2 ? specLightLast(b, F, a.lambda) : specLightLast(C[1], C[1].lobe, C[1].lambdaNext);
    return fp;
  });
  if (c.observer) c.observer->onLaneKept(lane);
  if (!(weight > 0.0f) || (!media && !visible(c, b, a))) return;
  const float value = Le * G * f * b.beta[lane] * transmittance(segment) / (a.pdfFwd * a.choicePdf);
  record(c, 1, t, Variant::kLightVertex, lane, value, weight);
  out[lane] += value * weight;
}

void connect(const Context& c, const std::vector<PathVertex>& L, LightFamily family, int s,
             const std::vector<PathVertex>& C, int t, float* out, VisibilityMemo* memo) {
  const PathVertex& a = L[size_t(s - 1)];
  const PathVertex& b = C[size_t(t - 1)];
  if (!a.scatters() || !b.scatters() || !a.connectible() || !b.connectible()) return;
  // An own join needs a fluorescent end, or two elastic ones and the mollifying kernel (below).
  if (family == LightFamily::Own && !(c.bandwidth > 0.0f) && !a.bsdf->has(BsdfFlags::Fluorescent) &&
      !b.bsdf->has(BsdfFlags::Fluorescent))
    return;
  // The lanes served: those that reach both ends on a shared subpath (it carries the camera
  // sample's); one on an own subpath, whose single wavelength meets one camera lane.
  int k0, k1;
  float laneScale = 1.0f;
  if (family == LightFamily::Shared) {
    k0 = std::max(a.firstLane(), b.firstLane()), k1 = std::min(a.endLane(c.lanes), b.endLane(c.lanes));
    laneScale = keptLaneScale(c, a.lane, b.lane);
  } else {
    const auto [lane, scale] = ownJoinLane(c, b);
    k0 = lane, k1 = lane + 1, laneScale = scale;
  }
  if (k0 >= k1) return;
  const bool media = c.scene.hasMedia();
  const PathVertex& aPrev = L[size_t(s - 2)];
  const PathVertex& bNext = C[size_t(t - 2)];
  const Vec3 d = b.p - a.p;
  const float dist2 = glm::dot(d, d);
  if (!(dist2 > 0.0f)) return;
  const Vec3 w = d / std::sqrt(dist2);  // from a to b
  const Bsdf &fa = *a.bsdf, &fb = *b.bsdf;
  const Vec3 aWi = fa.toLocal(towards(a, aPrev)), aWo = fa.toLocal(w);
  const Vec3 bWi = fb.toLocal(-w), bWo = fb.toLocal(towards(b, bNext));
  const float G = fa.cosineFactor(aWo) * fb.cosineFactor(bWi) / dist2;
  // The ends' wavelengths: an own join serves lane k0 only, and in a scene with media a join that
  // serves one lane has that lane's densities (their free flights depend on λ, docs/media.md §5).
  const bool oneLane = media && k1 - k0 == 1;
  float lambdaA = oneLane ? a.lambdaOf(c.lanes, k0) : a.lambda;
  float lambdaB = family == LightFamily::Own || oneLane ? b.lambdaOf(c.lanes, k0) : b.lambda;

  // The exact lobe pairs (docs/bdpt-mis.md §4), each with the connecting segment's wavelength as
  // a and b see it; the same for both except in the mollified elastic pair (§6), where a keeps the
  // light side's wavelength, b the camera side's, and a kernel joins them.
  struct Pair {
    SpectralLobe la, lb;
    float lambdaA, lambdaB;
    Variant variant;
  };
  Pair pairs[3];
  int n = 0;
  if (family == LightFamily::Shared) {
    // Each end's densities at its own wavelength: the lane's, or with several lanes one at which it
    // scatters (docs/bdpt-mis.md §10).
    pairs[n++] = {SpectralLobe::Elastic, SpectralLobe::Elastic, lambdaA, lambdaB, Variant::kStandard};
  } else {
    if (a.bsdf->has(BsdfFlags::Fluorescent))
      pairs[n++] = {SpectralLobe::Fluorescent, SpectralLobe::Elastic, lambdaB, lambdaB, Variant::kOwn};
    if (b.bsdf->has(BsdfFlags::Fluorescent))
      pairs[n++] = {SpectralLobe::Elastic, SpectralLobe::Fluorescent, lambdaA, lambdaA, Variant::kOwn};
    if (c.bandwidth > 0.0f && std::abs(a.lambda - lambdaB) < c.bandwidth)
      pairs[n++] = {SpectralLobe::Elastic, SpectralLobe::Elastic, a.lambda, lambdaB, Variant::kMollified};
  }
  const LightEnd end = storedLightEnd(L, s);
  // In a scene with media each pair's segment is traced before its weights, which need its optical
  // depths at the pair's wavelength (mollification, whose ends see two, is refused with media).
  bool checked = media, unoccluded = media;
  for (int i = 0; i < n; ++i) {
    Pair p = pairs[i];
    // f at both ends for each lane: the shared family's elastic pair at every lane's own wavelength.
    float fA[kMaxLanes], fB[kMaxLanes];
    bool any = false;
    for (int k = k0; k < k1; ++k) {
      // An end that several lanes reach scatters each elastically at its own wavelength (shared).
      const float lambda = c.lanes.lambda[k];
      const bool lanesA = family == LightFamily::Shared && a.allLanes(c.lanes);
      const bool lanesB = family == LightFamily::Shared && b.allLanes(c.lanes);
      fA[k] = a.bsdf->eval({TransportMode::Importance, p.la, lanesA ? lambda : a.lambda, lanesA ? lambda : p.lambdaA},
                           aWi, aWo);
      fB[k] = b.bsdf->eval({TransportMode::Radiance, p.lb, lanesB ? lambda : p.lambdaB, lanesB ? lambda : lambdaB}, bWi,
                           bWo);
      any = any || (fA[k] > 0.0f && fB[k] > 0.0f);
    }
    if (!any) continue;
    // A shared join is traced at the wavelength of the first lane it serves: through a medium, between
    // ends that several lanes reach, it serves that lane alone (laneZeroThroughMedia), with its
    // densities.
    SegmentDepth segment;
    const bool shared = family == LightFamily::Shared;
    if (media && !visible(c, a, b, shared ? a.lambdaOf(c.lanes, k0) : p.lambdaA, &segment)) return;
    if (shared && segment.inMedia && k1 - k0 > 1) {
      k1 = k0 + 1, laneScale *= float(c.lanes.n);
      p.lambdaA = lambdaA = a.lambdaOf(c.lanes, k0), p.lambdaB = lambdaB = b.lambdaOf(c.lanes, k0);
    }
    // The four densities next to the connection, for its lobes and wavelengths.
    const double pLightB =
        densityToward(c.scene, {TransportMode::Importance, p.la, lambdaA, p.lambdaA}, a, aWi, aWo, b, segment);
    const double pLightBNext = bNext.kind != Kind::Camera
                                   ? densityToward(c.scene, {TransportMode::Importance, p.lb, p.lambdaB, lambdaB}, b,
                                                   bWi, bWo, bNext, b.arrival)
                                   : 0.0;
    const double pCamA =
        densityToward(c.scene, {TransportMode::Radiance, p.lb, p.lambdaB, lambdaB}, b, bWo, bWi, a, segment);
    const double pCamAPrev =
        densityToward(c.scene, {TransportMode::Radiance, p.la, lambdaA, p.lambdaA}, a, aWo, aWi, aPrev, a.arrival);
    const Strategies& st = c.walk.strategies;
    // The beam ratios of the ends over the connection, each for the side that reaches it along it.
    const double beamA = st.merge.beam > 0.0 || st.merge.photonBeam > 0.0 ? cameraBeamRatio(c.scene, segment, a, p.lambdaB) : 0.0;
    const double beamB = st.merge.photonBeam > 0.0 ? lightBeamRatio(c.scene, segment, b, a, p.lambdaA) : 0.0;
    const bool photon = st.merge.photonBeam > 0.0;
    const double sineA = photon && a.inMedium() ? crossingSine(a.p, aPrev.p, b.p) : 0.0;
    const double sineB = photon && b.inMedium() ? crossingSine(b.p, a.p, bNext.p) : 0.0;
    const MisSums sides =
        lightSum(c, L, s, pCamA, lightMultiplicity(L, s - 1, p.la, p.lambdaA, st, false, true, beamA, sineA), pCamAPrev) +
        cameraSum(c, C, t, pLightB, cameraMultiplicity(C, t - 1, p.lb, p.lambdaB, st, true, beamB, sineB), pLightBNext);
    const MisSums here = joinMultiplicity(true, p.la, p.lb, st);
    MisSums own;
    (p.variant == Variant::kStandard ? own.shared : p.variant == Variant::kOwn ? own.own : own.mollified) = 1.0;
    const bool oneGroup = a.elasticBefore && b.elasticBefore && p.la == SpectralLobe::Elastic && p.lb == SpectralLobe::Elastic;
    const bool lanesKept = a.lanesKept && b.lanesKept;
    float weight[kMaxLanes];
    laneWeights(c, k0, k1, weight, [&](int k) { return fA[k] > 0.0f && fB[k] > 0.0f; }, [&](int k) {
      // The path's first wavelength: lane k's on a shared subpath, the own subpath's own.
      const MisFactors f = family == LightFamily::Shared
                               ? factors(c, L[0].light, a.lambdaOf(c.lanes, k), k, c.lanes.pdf[k], oneGroup,
                                         lanesKept)
                               : factors(c, L[0].light, L[0].lambda, -1, c.lanes.pdf[k], oneGroup, lanesKept,
                                         c.walk.lightFirst ? L[0].choicePdf : 0.0f);
      return weigh(c, s, t, p.variant, own, here + sides, f, [&](const MisFactors& g) {
        FullPath fp = layout(c, &L, s, C, t, end, g, true);
        fp.v[size_t(s - 1)].lobe = p.la;
        fp.v[size_t(s)].lobe = p.lb;
        fp.v[size_t(s)].pdfLight = pLightB;
        fp.v[size_t(s + 1)].pdfLight = pLightBNext;
        fp.v[size_t(s - 1)].pdfCam = pCamA;
        fp.v[size_t(s - 1)].cameraBeam = beamA;
        fp.v[size_t(s)].lightBeam = beamB;
        fp.v[size_t(s - 1)].beamSine = sineA;
        fp.v[size_t(s)].beamSine = sineB;
        fp.v[size_t(s - 2)].pdfCam = pCamAPrev;
        const PathVertex& x1 = L[1];
        fp.specCam1 = s == 2 ? specCamera(x1, p.la, x1.lambda, p.lambdaA) : specCamera(x1, x1.lobe, x1.lambda, x1.lambdaNext);
        fp.specLightLast = t == 2 ? specLightLast(b, p.lb, p.lambdaB) : specLightLast(C[1], C[1].lobe, C[1].lambdaNext);
        return fp;
      });
    });
    if (std::none_of(weight + k0, weight + k1, [](float w) { return w > 0.0f; })) continue;
    if (!checked) {
      checked = true;
      unoccluded = memo ? memo->get(s, t, [&] { return visible(c, a, b); }) : visible(c, a, b);
    }
    if (!unoccluded) return;
    // Mollified: the delta δ(λ_a − λ_b) of the elastic pair widened to K_h (Jung et al. 2020),
    // renormalised to its mass inside the wavelength range (docs/bdpt-mis.md eq. 5).
    const WavelengthRange& r = c.scene.range;
    const float kernel = p.variant == Variant::kMollified
                             ? wavelengthKernel(a.lambda - lambdaB, c.bandwidth) /
                                   wavelengthKernelMass(r.min - lambdaB, r.max - lambdaB, c.bandwidth)
                             : 1.0f;
    for (int k = k0; k < k1; ++k) {
      const float value = a.beta[family == LightFamily::Shared ? k : 0] * fA[k] * G * fB[k] * b.beta[k] * kernel *
                          laneScale * transmittance(segment);
      record(c, s, t, p.variant, k, value, weight[k]);
      out[k] += value * weight[k];
    }
  }
}

void connectToCamera(const Context& c, const std::vector<PathVertex>& L, LightFamily family, int s, Vec2 lensSample,
                     std::vector<Splat>& splats, VisibilityMemo* memo) {
  const PathVertex& a = L[size_t(s - 1)];
  if (a.kind == Kind::Infinite || !a.connectible()) return;
  PathVertex cam;
  cam.kind = Kind::Camera;
  cam.deltaPosition = c.scene.camera.pinhole();
  cam.parallelRays = c.scene.camera.parallelRays();
  // The camera's density of a: its ray's over the whole film, from the lens point, times the
  // reconstruction filter's coverage there (the sensor's density of the wavelength arriving is a
  // factor, mis_sums.h).
  const Camera& camera = c.scene.camera;
  const PixelFilter& filter = c.scene.pixelFilter;
  const auto makeLink = [&] {
    CameraLink l{camera.connect(a.p, lensSample, filter.filmMargin())};
    if (l.connection) {
      cam.p = l.connection->lensPoint;
      l.pdfCam = toAreaDensity(l.connection->pdfRay * filter.coverage(l.connection->pixel, camera.width(), camera.height()),
                               cam, a);
    }
    return l;
  };
  const CameraLink link = memo ? memo->link(s, makeLink) : makeLink();
  const std::optional<Camera::Connection>& conn = link.connection;
  if (!conn) return;
  cam.p = conn->lensPoint;  // also where the memo kept the other view's link
  // The wavelength arriving at the camera: the light itself for s = 1, else the one a's sampled
  // spectral event sends towards the camera; with several lanes at a, each lane's own.
  float lambda = s == 1 ? a.lambda : a.lambdaNext;
  const bool lanes = a.allLanes(c.lanes);
  const bool shared = family == LightFamily::Shared;
  const Variant variant = shared ? Variant::kStandard : Variant::kOwn;
  // In a scene with media the segment to the lens is traced first: the camera's density of a needs
  // its optical depths. Where several lanes reach a, it is traced at lane 0's wavelength, and
  // through a medium it serves lane 0 alone (laneZeroThroughMedia), with lane 0's densities.
  const bool media = c.scene.hasMedia();
  SegmentDepth segment;
  if (media && !visible(c, a, cam, lanes ? c.lanes.lambda[0] : lambda, &segment)) return;
  const bool laneZero = lanes && segment.inMedia;
  if (laneZero) lambda = c.lanes.lambda[0];
  const float lambdaA = laneZero ? lambda : a.lambda;
  const double pCamA = link.pdfCam * flightFactor(c.scene, TransportMode::Radiance, segment, a, lambda);
  const LightEnd end = storedLightEnd(L, s);
  float value[kMaxLanes];
  bool any = false;
  MisSums here, own, sides;
  bool oneGroup = true;
  double pCamAPrev = 0.0, beamA = 0.0, sineA = 0.0;  // beamA: the camera's beam ratio at a (s ≥ 2), sineA its sin θ
  if (s == 1) {
    // The light itself, seen directly (area lights only; weight 0 where the camera's s = 0 adds it
    // exactly, see emitterHit).
    if (a.kind != Kind::Light || a.deltaPosition || c.directXyz) return;
    const AreaEmission& em = *static_cast<const AreaLight&>(*c.scene.lights[size_t(a.light)]).shape().emission;
    for (int k = a.firstLane(); k < a.endLane(c.lanes); ++k) {
      const float Le = em.eval(lanes ? c.lanes.lambda[k] : lambda, a.n, conn->wi);
      value[k] = Le * std::abs(glm::dot(a.n, conn->wi)) / (a.pdfFwd * a.choicePdf);
      any = any || Le > 0.0f;
    }
    if (laneZero) laneZeroThroughMedia(c, value);
    here = directLightMultiplicity(true, c.walk.strategies);
    (shared ? own.shared : own.ownSplat) = 1.0;
    sides = lightEndSum(pCamA, a.pdfFwd);
  } else {
    // The light side's own spectral event at a (λ_o from e when fluorescent): the sensor
    // responds at the wavelength it chose.
    if (!a.eventSampled) return;
    const PathVertex& aPrev = L[size_t(s - 2)];
    const Bsdf& f = *a.bsdf;
    const Vec3 wi = f.toLocal(towards(a, aPrev)), wo = f.toLocal(conn->wi);
    for (int k = a.firstLane(); k < a.endLane(c.lanes); ++k) {
      const float fa =
          lanes ? a.bsdf->eval({TransportMode::Importance, a.lobe, c.lanes.lambda[k], c.lanes.lambda[k]}, wi, wo)
                : a.bsdf->eval({TransportMode::Importance, a.lobe, a.lambda, lambda}, wi, wo);
      value[k] = a.beta[k] * fa * f.cosineFactor(wo) / a.spectralPdf;
      any = any || fa > 0.0f;
    }
    if (laneZero) laneZeroThroughMedia(c, value);
    pCamAPrev = densityToward(c.scene, {TransportMode::Radiance, a.lobe, lambdaA, lambda}, a, wo, wi, aPrev, a.arrival);
    here = lightTracingMultiplicity(true, a.spectralPdf, c.walk.strategies);
    (shared ? own.shared : own.ownSplat) = double(a.spectralPdf) * a.spectralPdf;
    // a, next to the camera, is the path's first gather vertex.
    const MergeEta& eta = c.walk.strategies.merge;
    beamA = eta.beam > 0.0 || eta.photonBeam > 0.0 ? cameraBeamRatio(c.scene, segment, a, lambda) : 0.0;
    sineA = eta.photonBeam > 0.0 && a.inMedium() ? crossingSine(a.p, aPrev.p, cam.p) : 0.0;
    sides = lightSum(c, L, s, pCamA,
                     lightMultiplicity(L, s - 1, a.lobe, a.lambdaNext, c.walk.strategies, true, true, beamA, sineA),
                     pCamAPrev);
    oneGroup = a.elasticBefore && a.lobe == SpectralLobe::Elastic;
  }
  for (int k = a.firstLane(); k < a.endLane(c.lanes); ++k) value[k] *= transmittance(segment);
  if (!any) return;
  const int k0 = a.firstLane(), k1 = a.endLane(c.lanes);
  float weight[kMaxLanes];
  laneWeights(c, k0, k1, weight, [&](int k) { return value[k] > 0.0f; }, [&](int k) {
    // A shared lane's wavelength is the sensor's lane k; an own subpath's arrives from the light.
    const bool lanesKept = s == 1 || a.lanesKept;
    const MisFactors mf = shared ? factors(c, L[0].light, a.lambdaOf(c.lanes, k), k, c.lanes.pdf[k], oneGroup,
                                           lanesKept)
                                 : factors(c, L[0].light, L[0].lambda, -1, c.sensor.pdf(lambda), oneGroup, lanesKept,
                                           c.walk.lightFirst ? L[0].choicePdf : 0.0f);
    return weigh(c, s, 1, variant, own, here + sides, mf, [&](const MisFactors& g) {
      const std::vector<PathVertex> camOnly{cam};
      FullPath fp = layout(c, &L, s, camOnly, 1, end, g, true);
      const int last = s;
      fp.v[size_t(last - 1)].pdfCam = pCamA;
      fp.v[size_t(last - 1)].cameraBeam = beamA;
      fp.v[size_t(last - 1)].beamSine = sineA;
      if (s == 1) {
        fp.lightSeenByPinhole = true;
      } else {
        fp.v[size_t(last - 2)].pdfCam = pCamAPrev;
        const PathVertex& x1 = L[1];
        fp.specCam1 = s == 2 ? specCamera(x1, a.lobe, lambdaA, lambda) : specCamera(x1, x1.lobe, x1.lambda, x1.lambdaNext);
        fp.specLightLast = a.spectralPdf;
      }
      return fp;
    });
  });
  if (std::none_of(weight + k0, weight + k1, [](float w) { return w > 0.0f; })) return;
  if (!media && !(memo ? memo->get(s, 1, [&] { return visible(c, a, cam); }) : visible(c, a, cam))) return;
  // Importance W_j·cosθ/d² of the pixel, per light subpath (w·h of them per sample per pixel); a
  // shared lane's wavelength was the sensor's sample, one of n.
  const float perPath = 1.0f / (float(c.scene.camera.width()) * float(c.scene.camera.height()));
  Vec3 sum(0.0f), unweighted(0.0f);  // the lanes' XYZ
  for (int k = a.firstLane(); k < a.endLane(c.lanes); ++k) {
    if (!(value[k] > 0.0f)) continue;
    const float lambdaK = lanes ? c.lanes.lambda[k] : lambda;
    float sensorWeight = perPath;
    if (shared) sensorWeight /= float(c.lanes.n) * c.lanes.pdf[k];
    const float v = value[k] * conn->importance * sensorWeight;
    // A shared lane's wavelength is the sensor's lane k (whose response is known).
    const Vec3 xyz = shared ? c.lanes.response[k] * v : Observer::cie1931().weight(lambdaK) * v;
    if (c.spectralSplats) splats.push_back({conn->pixel, xyz * weight[k], lambdaK, v * weight[k]});
    if (c.observer) c.observer->onContribution(k, conn->pixel, xyz * weight[k]);
    sum += xyz * weight[k];
    unweighted += xyz;
  }
  if (!c.spectralSplats) splats.push_back({conn->pixel, sum});
  if (c.observer) c.observer->onStrategy({conn->pixel, sum, unweighted, s, 1, uint8_t(variant)});
}

void connectSubpaths(const Context& c, const std::vector<PathVertex>& C, const std::vector<PathVertex>& LS,
                     const std::vector<PathVertex>& LO, Sampler& rng, std::vector<Splat>& splats, float* out,
                     Vec3& xyz) {
  const int maxDepth = c.walk.maxDepth;
  // The merged subpath's two views share their common vertices' visibility (docs/bdpt-mis.md §11).
  thread_local VisibilityMemo sharedVisibility;
  VisibilityMemo* memo = c.sharedLightVertices > 0 ? &sharedVisibility : nullptr;
  if (memo) memo->reset(std::min(c.sharedLightVertices, int(std::min(LS.size(), LO.size()))), int(C.size()));
  std::fill(out, out + c.lanes.n, 0.0f);
  xyz = Vec3(0.0f);
  // Strategies with t ≥ 2 estimate this pixel's radiance at the sensor's wavelengths.
  // Paths of one segment (t = 2 hitting an emitter, s = 1 seen by the camera) have no scattering vertex.
  const int fewest = c.walk.hideEmitters ? 2 : 1;
  for (int t = 2; t <= int(C.size()); ++t) {
    if (t > fewest) emitterHit(c, C, t, out, xyz);
    if (!C[size_t(t - 1)].scatters()) continue;
    if (t - 1 <= maxDepth) {
      nextEvent(c, C, t, rng, out);
      if (!LO.empty()) connectLightVertex(c, LO, C, t, out);
    }
    for (int s = 2; s <= int(LS.size()) && (s - 1) + (t - 1) <= maxDepth; ++s)
      connect(c, LS, LightFamily::Shared, s, C, t, out, memo);
    for (int s = 2; s <= int(LO.size()) && (s - 1) + (t - 1) <= maxDepth; ++s)
      connect(c, LO, LightFamily::Own, s, C, t, out, memo);
  }
  // t = 1: light subpath vertices seen by the camera, each through a lens point of its own, splatted
  // to their pixels.
  for (int s = fewest; s <= int(LS.size()) && s - 1 <= maxDepth; ++s)
    connectToCamera(c, LS, LightFamily::Shared, s, c.scene.camera.sampleLens(rng), splats, memo);
  for (int s = fewest; s <= int(LO.size()) && s - 1 <= maxDepth; ++s)
    connectToCamera(c, LO, LightFamily::Own, s, c.scene.camera.sampleLens(rng), splats, memo);
}

}  // namespace kasha::bidir
