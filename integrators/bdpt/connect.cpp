#include "integrators/bdpt/connect.h"

#include <algorithm>

#include "core/color.h"
#include "integrators/bdpt/subpath_mis.h"
#include "integrators/progressive_schedule.h"

namespace kasha::bdpt {
namespace {

using Kind = PathVertex::Kind;

Vec3 towards(const PathVertex& from, const PathVertex& to) {
  return to.kind == Kind::Infinite ? -to.dir : glm::normalize(to.p - from.p);
}

// Area density at `target` (per sr at infinity) of a solid-angle density at `at`; vertices no
// other strategy can sample (the pinhole, delta lights) get 0.
double toArea(const Scene& scene, float pdfSA, const PathVertex& at, const PathVertex& target) {
  if (target.kind == Kind::Camera || target.deltaPosition) return 0.0;
  if (target.kind == Kind::Infinite) return scene.lights[size_t(target.light)]->isDelta() ? 0.0 : pdfSA;
  return toAreaDensity(pdfSA, at, target);
}

// Camera-side (Radiance) density of `target` sampled at `at`, whose camera-side neighbour is
// `camNext`: the spectral event (lobe, λ_in given λ_out) and the direction.
double cameraSide(const Scene& scene, const PathVertex& at, const PathVertex& camNext, const PathVertex& target,
                  SpectralLobe lobe, float lambdaIn, float lambdaOut) {
  const Bsdf& f = *at.bsdf;
  const Vec3 wo = f.toLocal(towards(at, camNext)), wi = f.toLocal(towards(at, target));
  const float pdf = at.bsdf->spectralPdf(TransportMode::Radiance, lambdaOut, lambdaIn, lobe) *
                    at.bsdf->directionPdf(TransportMode::Radiance, wo, wi, lobe, lambdaIn, lambdaOut);
  return toArea(scene, pdf, at, target);
}

// Light-side (Importance) density of `target` sampled at `at`, whose light-side neighbour is
// `lightPrev`.
double lightSide(const Scene& scene, const PathVertex& at, const PathVertex& lightPrev, const PathVertex& target,
                 SpectralLobe lobe, float lambdaIn, float lambdaOut) {
  const Bsdf& f = *at.bsdf;
  const Vec3 wi = f.toLocal(towards(at, lightPrev)), wo = f.toLocal(towards(at, target));
  const float pdf = at.bsdf->spectralPdf(TransportMode::Importance, lambdaIn, lambdaOut, lobe) *
                    at.bsdf->directionPdf(TransportMode::Importance, wi, wo, lobe, lambdaIn, lambdaOut);
  return toArea(scene, pdf, at, target);
}

// The light end x_0 seen from its neighbour x_1: its positional densities.
struct LightEnd {
  double pdf0 = 0.0;    // pL_0: x_0's position (per sr at infinity), also next-event estimation's
  double pdf1 = 0.0;    // pL_1: the light side's density of x_1 (0 if x_1 is the camera)
  bool finite = false;  // x_0 is at a finite position
};

LightEnd lightEnd(const Context& c, int light, const PathVertex& x0, const PathVertex& x1) {
  const Light& L = *c.scene.lights[size_t(light)];
  const Vec3 w = L.atInfinity() ? x0.dir : glm::normalize(x1.p - x0.p);
  float pdfPos = 0.0f, pdfDir = 0.0f;
  L.emissionPdfs(x0.p, x0.n, w, pdfPos, pdfDir);
  LightEnd e;
  e.pdf0 = L.atInfinity() ? pdfDir : pdfPos;
  if (x1.kind != Kind::Camera)
    e.pdf1 = L.atInfinity() ? double(pdfPos) * std::abs(glm::dot(x1.n, w)) : toAreaDensity(pdfDir, x0, x1);
  e.finite = !L.atInfinity();
  return e;
}

// The light end of a light subpath whose first s vertices a strategy uses, from what the subpath
// stored (x_1 is the camera when s = 1).
LightEnd storedLightEnd(const std::vector<PathVertex>& L, int s) {
  return {L[0].pdfFwd, s >= 2 ? double(L[1].pdfFwd) : 0.0, L[0].kind == Kind::Light};
}

// The wavelength factors of the weights (mis_sums.h, docs/bdpt-mis.md §10) for a path whose light
// end is `light` at wavelength lambda0 and whose last wavelength the sensor draws with sensorPdf.
// lane: the camera sample's lane whose wavelength lambda0 is (the path has one group), or −1.
// The camera family's light choice is the true one, the lanes' mixture, where it is the same for
// every strategy that can make the path (one group, the shared family alone); with the own family
// as well, every strategy's choice is taken as p(light | λ_0), a function of the path alone, so
// that the weights stay a partition of unity for each lane (the estimates divide by the true one).
// lanesKept: every interior vertex of the path keeps the lanes (MisFactors::laneGain). ownStart: the
// own family's ℓ where the caller knows it (an own subpath's L[0].choicePdf), else 0.
MisFactors factors(const Context& c, int light, float lambda0, int lane, double sensorPdf, bool oneGroup,
                   bool lanesKept, float ownStart = 0.0f) {
  MisFactors f;
  f.sharedFamily = c.families.shared;
  f.ownFamily = c.families.independent;
  f.sensorPdf = sensorPdf;
  f.oneGroup = oneGroup;
  if (lanesKept && f.ownFamily && c.walk.lightFirst) f.laneGain = c.lanes.n;
  const bool table = lane >= 0 && c.lanes.lights;
  if (table && oneGroup && !f.ownFamily) {
    f.cameraChoice = c.lanes.lights->probability(size_t(light));
    return f;
  }
  f.cameraChoice = table ? c.lanes.lights->laneProbability(size_t(light), lane)
                         : c.scene.lightSelector->probability(size_t(light), lambda0);
  if (f.ownFamily && c.walk.lightFirst) {
    // The merged subpath's start (light_first.h): Q(l)·p_l(λ_0), tabulated at the lanes.
    const LightFirstStart& start = *c.walk.lightFirst;
    if (ownStart > 0.0f)
      f.ownChoice = ownStart;
    else if (table && c.lanes.ownStart)
      f.ownChoice = c.lanes.ownStart[size_t(lane) * c.scene.lights.size() + size_t(light)];
    else
      f.ownChoice = double(start.lightProbability(size_t(light))) * start.wavelengthPdf(size_t(light), lambda0);
  } else if (f.ownFamily) {
    const double pLight = table ? c.lanes.lightPdf[lane] : c.walk.lightWavelengths->pdf(lambda0);
    f.ownChoice = pLight * f.cameraChoice;
    if (c.bandwidth > 0.0f) f.mollifyWidth = 1.0 / wavelengthKernel(0.0f, c.bandwidth);
  }
  return f;
}

// The full recomputation (test oracle, docs/bdpt-mis.md §5): the stored densities of L[0..s−1],
// C[0..t−1] laid out as x_0 … x_k, with the light end's.
FullPath layout(const Context& c, const std::vector<PathVertex>* L, int s, const std::vector<PathVertex>& C, int t,
                const LightEnd& end, const MisFactors& f) {
  FullPath fp;
  fp.families = c.families;
  fp.sensorPdf = f.sensorPdf;
  fp.laneGain = f.laneGain;
  fp.cameraChoice = f.cameraChoice;
  fp.ownChoice = f.ownChoice;
  fp.mollifyWidth = f.mollifyWidth;
  const int k = s + t - 1;
  fp.v.resize(size_t(k + 1));
  for (int i = 0; i < s; ++i) {
    const PathVertex& v = (*L)[size_t(i)];
    fp.v[size_t(i)] = {v.pdfFwd, v.pdfRev, v.lobe, v.connectible()};
  }
  for (int j = 0; j < t; ++j) {
    const PathVertex& v = C[size_t(j)];
    fp.v[size_t(k - j)] = {v.pdfRev, v.pdfFwd, v.lobe, v.connectible()};
  }
  fp.v[size_t(k)].pdfCam = 1.0;  // the pinhole is a delta: every strategy shares it
  fp.v[size_t(k)].pdfLight = 0.0;
  // The light end where no light subpath vertex stores it.
  if (s == 0) fp.v[0].pdfLight = end.pdf0;
  if (s <= 1 && end.pdf1 > 0.0) fp.v[1].pdfLight = end.pdf1;
  fp.v[0].connectible = true;
  fp.pdfNee = fp.v[0].pdfLight;  // p_A: the light choice is cameraChoice
  fp.lightVertexConnectible = end.finite;
  return fp;
}

// Camera-side spectral density of x_1's event (needed by next-event estimation's density).
double specCamera(const PathVertex& x1, SpectralLobe lobe, float lambda0, float lambda1) {
  return x1.bsdf->spectralPdf(TransportMode::Radiance, lambda1, lambda0, lobe);
}

// Light-side spectral density of x_{k−1}'s event, which the t = 1 strategy samples: x_{k−1} is
// the camera subpath's first hit C[1], with its own sampled event unless it is a connection
// vertex (then `lobe`/`lambdaIn` give the connection's).
double specLightLast(const PathVertex& c1, SpectralLobe lobe, float lambdaIn) {
  return c1.bsdf->spectralPdf(TransportMode::Importance, lambdaIn, c1.lambda, lobe);
}

// A strategy's weight from the recursive sums: its own c² over the path's whole sum
// (docs/bdpt-mis.md eq. 11). With c.oracle set, the full recomputation `full(f)` is recorded beside it.
template <class Full>
float weigh(const Context& c, int s, int t, Variant v, const MisSums& own, const MisSums& total, const MisFactors& f,
            Full&& full) {
  const double sum = combine(total, f);
  const float w = sum > 0.0 ? float(combine(own, f) / sum) : 0.0f;
  if (c.oracle) c.oracle->push_back({s, t, uint8_t(v), w, full(f)});
  return w;
}

// The lane an own-family join at camera vertex b serves, and its factor: with several lanes at b,
// one chosen uniformly with b's own number, its estimate times n (an unbiased one-sample estimate
// of the sum over the lanes).
std::pair<int, float> ownJoinLane(const Context& c, const PathVertex& b) {
  if (!b.allLanes(c.lanes)) return {b.firstLane(), 1.0f};
  return {std::min(int(b.laneU * float(c.lanes.n)), c.lanes.n - 1), float(c.lanes.n)};
}

// Each lane's weight in [k0, k1) where active(k), from weighLane(k): per lane where the own family
// runs (its factors differ between lanes), once for all otherwise (docs/bdpt-mis.md §10).
template <class Active, class WeighLane>
void laneWeights(const Context& c, int k0, int k1, float* w, Active&& active, WeighLane&& weighLane) {
  int first = -1;
  for (int k = k0; k < k1; ++k) {
    w[k] = 0.0f;
    if (!active(k)) continue;
    if (first >= 0 && !c.families.independent) {
      w[k] = w[first];
      continue;
    }
    w[k] = weighLane(k);
    first = k;
  }
}

// XYZ per unit radiance of lane k at the camera: W(λ_k)/(n·p(λ_k)).
Vec3 laneScale(const Context& c, int k) {
  return Observer::cie1931().weight(c.lanes.lambda[k]) / (float(c.lanes.n) * c.lanes.sensorPdf[k]);
}

// Records lane k's share of a strategy at the camera sample's pixel (strategies with t ≥ 2).
void record(const Context& c, int s, int t, Variant v, int k, float value, float weight) {
  if (c.log && value != 0.0f)
    c.log->push_back({c.pixel, laneScale(c, k) * (value * weight), laneScale(c, k) * value, s, t, uint8_t(v)});
}

// The radiance an emitter vertex e sends towards `next` at wavelength lambda.
float emitted(const Context& c, const PathVertex& e, const PathVertex& next, float lambda) {
  if (e.kind == Kind::Infinite) return c.scene.environment()->Le(lambda, -e.dir);
  return static_cast<const AreaLight&>(*c.scene.lights[size_t(e.light)]).shape().emission->eval(lambda, e.n,
                                                                                                towards(e, next));
}

bool visible(const Context& c, const PathVertex& a, const PathVertex& b) {
  ++c.counter.shadow;
  if (b.kind == Kind::Infinite) return !c.scene.accel->occluded(offsetPoint(a.p, a.n, -b.dir), -b.dir, kInf);
  const Vec3 d = b.p - a.p;
  const float dist = glm::length(d);
  const Vec3 w = d / dist;
  const Vec3 o = glm::dot(a.n, a.n) > 0.0f ? offsetPoint(a.p, a.n, w) : a.p;
  const float shorten = glm::dot(b.n, b.n) > 0.0f ? rayEpsilon(b.p) : 0.0f;
  return !c.scene.accel->occluded(o, w, dist * (1.0f - 1e-4f) - shorten - rayEpsilon(a.p));
}

// The camera side's sum at a connection through C[t−1] (docs/bdpt-mis.md eq. 10): C[t−1] with the
// light side's density pLast and `mLast` the M of the strategy with t − 1 camera vertices; C[t−2]
// with the light side's density pBefore.
MisSums cameraSum(const std::vector<PathVertex>& C, int t, double pLast, const MisSums& mLast, double pBefore) {
  const PathVertex& b = C[size_t(t - 1)];
  const PathVertex& bNext = C[size_t(t - 2)];
  return sideSum(b.sums, densityRatio(pBefore, bNext.pdfFwd), cameraMultiplicity(C, t - 2), densityRatio(pLast, b.pdfFwd),
                 mLast);
}

// The light side's sum at a connection through L[s−1] (s ≥ 2; eq. 10): L[s−1] with the camera
// side's density pLast and `mLast` the M of the strategy with s − 1 light vertices; L[s−2] with
// the camera side's density pBefore.
MisSums lightSum(const std::vector<PathVertex>& L, int s, double pLast, const MisSums& mLast, double pBefore) {
  const PathVertex& a = L[size_t(s - 1)];
  const PathVertex& aPrev = L[size_t(s - 2)];
  return sideSum(a.sums, densityRatio(pBefore, aPrev.pdfFwd), lightMultiplicity(L, s - 2), densityRatio(pLast, a.pdfFwd),
                 mLast);
}

// The light side's sum of a strategy whose light subpath ends at x_0 (s = 1): the camera side's
// density pCam0 of it over the light side's, pLight0.
MisSums lightEndSum(double pCam0, double pLight0) { return extend({}, densityRatio(pCam0, pLight0), hitMultiplicity()); }

}  // namespace

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
    if (c.log) c.log->push_back({c.pixel, value, value, 0, t, uint8_t(Variant::kStandard)});
    return;
  }
  float Le[kMaxLanes];
  bool any = false;
  for (int k = e.firstLane(); k < e.endLane(c.lanes); ++k) {
    Le[k] = emitted(c, e, next, e.lambdaOf(c.lanes, k));
    any = any || Le[k] > 0.0f;
  }
  if (!any) return;
  const LightEnd end = lightEnd(c, e.light, e, next);
  const int k = t - 1;
  // The strategies with one light vertex: next-event estimation and the light vertex at x_1, or
  // for k = 1 the light seen by the camera.
  const MisSums m1 = k >= 2 ? firstVertexMultiplicity(next.connectible(), next.lobe, next.spectralPdf, end.finite)
                            : directLightMultiplicity(e.kind == Kind::Surface);
  const MisSums own = hitMultiplicity();
  const MisSums total = own + cameraSum(C, t, end.pdf0, m1, end.pdf1);
  float weight[kMaxLanes];
  laneWeights(c, e.firstLane(), e.endLane(c.lanes), weight, [&](int j) { return Le[j] > 0.0f; }, [&](int j) {
    const MisFactors f = factors(c, e.light, e.lambdaOf(c.lanes, j), e.elasticBefore ? j : -1, c.lanes.sensorPdf[j],
                                 e.elasticBefore, next.lanesKept);
    return weigh(c, 0, t, Variant::kStandard, own, total, f, [&](const MisFactors& g) {
      FullPath fp = layout(c, nullptr, 0, C, t, end, g);
      if (k >= 2) {
        fp.specCam1 = next.spectralPdf;
        fp.specLightLast = specLightLast(C[1], C[1].lobe, C[1].lambdaNext);
      } else {
        fp.lightSeenByPinhole = e.kind == Kind::Surface;
      }
      return misWeight(fp, 0, Variant::kStandard);
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
    const float fx = lanes ? x1.bsdf->eval(TransportMode::Radiance, wi, wo, lambda, lambda, x1.lobe)
                           : x1.bsdf->eval(TransportMode::Radiance, wi, wo, lambda0, x1.lambda, x1.lobe);
    // The light's geometry does not depend on λ: the same point at every lane's wavelength.
    const float Li = lanes ? light.Li(*ls, lambda) : ls->Li;
    value[k] = fx > 0.0f ? x1.beta[k] * fx * std::abs(wi.z) / x1.spectralPdf * Li / (pSel * ls->pdf) : 0.0f;
    any = any || value[k] > 0.0f;
  }
  if (!any || !visible(c, x1, x0)) return;
  const int lightIndex = int(li);  // a structured binding cannot be captured (clang 14)
  const LightEnd end = lightEnd(c, lightIndex, x0, x1);
  const double pCam0 = cameraSide(c.scene, x1, x2, x0, x1.lobe, lambda0, x1.lambda);
  const double pLight2 = x2.kind != Kind::Camera ? lightSide(c.scene, x1, x0, x2, x1.lobe, lambda0, x1.lambda) : 0.0;
  const MisSums m1 = firstVertexMultiplicity(true, x1.lobe, x1.spectralPdf, end.finite);
  MisSums own;
  own.nee = x1.spectralPdf * double(x1.spectralPdf);
  const MisSums total = m1 + lightEndSum(pCam0, end.pdf0) + cameraSum(C, t, end.pdf1, cameraMultiplicity(C, t - 1), pLight2);
  float weight[kMaxLanes];
  laneWeights(c, x1.firstLane(), x1.endLane(c.lanes), weight, [&](int k) { return value[k] > 0.0f; }, [&](int k) {
    const MisFactors f = factors(c, lightIndex, lanes ? c.lanes.lambda[k] : lambda0, cameraGroup ? k : -1,
                                 c.lanes.sensorPdf[k], cameraGroup, x1.lanesKept);
    return weigh(c, 1, t, Variant::kStandard, own, total, f, [&](const MisFactors& g) {
      PathVertex lightVertex = x0;
      lightVertex.pdfFwd = float(end.pdf0);
      lightVertex.pdfRev = float(pCam0);
      const std::vector<PathVertex> L1{lightVertex};
      FullPath fp = layout(c, &L1, 1, C, t, end, g);
      if (x2.kind != Kind::Camera) fp.v[2].pdfLight = pLight2;
      fp.specCam1 = x1.spectralPdf;
      fp.specLightLast = specLightLast(C[1], C[1].lobe, C[1].lambdaNext);
      return misWeight(fp, 1, Variant::kStandard);
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
  if (a.kind != Kind::Light || b.kind != Kind::Surface || !b.connectible() || !b.bsdf->has(BsdfFlags::Fluorescent)) return;
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
  const float f = b.bsdf->eval(TransportMode::Radiance, bWi, bWo, a.lambda, b.lambda, F);
  if (!(f > 0.0f)) return;
  const int lane = b.firstLane();
  const float cosA = glm::dot(a.n, a.n) > 0.0f ? std::abs(glm::dot(a.n, w)) : 1.0f;
  const float G = cosA * std::abs(bWi.z) / dist2;
  const LightEnd end = lightEnd(c, a.light, a, b);
  const double pCam0 = cameraSide(c.scene, b, bNext, a, F, a.lambda, b.lambda);
  const double pLight2 = bNext.kind != Kind::Camera ? lightSide(c.scene, b, a, bNext, F, a.lambda, b.lambda) : 0.0;
  const double specCam1 = specCamera(b, F, a.lambda, b.lambda);
  MisSums own;
  own.own = 1.0;
  const MisSums total = firstVertexMultiplicity(true, F, specCam1, true) + lightEndSum(pCam0, a.pdfFwd) +
                        cameraSum(C, t, end.pdf1, cameraMultiplicity(C, t - 1, F, a.lambda), pLight2);
  const MisFactors mf = factors(c, a.light, a.lambda, -1, c.lanes.sensorPdf[lane], false, false,
                                c.walk.lightFirst ? a.choicePdf : 0.0f);
  const float weight = weigh(c, 1, t, Variant::kLightVertex, own, total, mf, [&](const MisFactors& g) {
    FullPath fp = layout(c, &L, 1, C, t, end, g);
    fp.v[1].lobe = F;
    fp.v[0].pdfCam = pCam0;
    if (bNext.kind != Kind::Camera) fp.v[2].pdfLight = pLight2;
    fp.specCam1 = specCam1;
    fp.specLightLast = t == 2 ? specLightLast(b, F, a.lambda) : specLightLast(C[1], C[1].lobe, C[1].lambdaNext);
    return misWeight(fp, 1, Variant::kLightVertex);
  });
  if (!(weight > 0.0f) || !visible(c, b, a)) return;
  const float value = Le * G * f * b.beta[lane] / (a.pdfFwd * a.choicePdf);
  record(c, 1, t, Variant::kLightVertex, lane, value, weight);
  out[lane] += value * weight;
}

void connect(const Context& c, const std::vector<PathVertex>& L, LightFamily family, int s,
             const std::vector<PathVertex>& C, int t, float* out, VisibilityMemo* memo) {
  const PathVertex& a = L[size_t(s - 1)];
  const PathVertex& b = C[size_t(t - 1)];
  if (a.kind != Kind::Surface || b.kind != Kind::Surface || !a.connectible() || !b.connectible()) return;
  // The lanes served: those that reach both ends on a shared subpath (it carries the camera
  // sample's); one on an own subpath, whose single wavelength meets one camera lane.
  int k0, k1;
  float laneScale = 1.0f;
  if (family == LightFamily::Shared) {
    k0 = std::max(a.firstLane(), b.firstLane()), k1 = std::min(a.endLane(c.lanes), b.endLane(c.lanes));
  } else {
    const auto [lane, scale] = ownJoinLane(c, b);
    k0 = lane, k1 = lane + 1, laneScale = scale;
  }
  if (k0 >= k1) return;
  const PathVertex& aPrev = L[size_t(s - 2)];
  const PathVertex& bNext = C[size_t(t - 2)];
  const Vec3 d = b.p - a.p;
  const float dist2 = glm::dot(d, d);
  if (!(dist2 > 0.0f)) return;
  const Vec3 w = d / std::sqrt(dist2);  // from a to b
  const Bsdf &fa = *a.bsdf, &fb = *b.bsdf;
  const Vec3 aWi = fa.toLocal(towards(a, aPrev)), aWo = fa.toLocal(w);
  const Vec3 bWi = fb.toLocal(-w), bWo = fb.toLocal(towards(b, bNext));
  const float G = std::abs(aWo.z) * std::abs(bWi.z) / dist2;
  // b's wavelength: an own join serves lane k0 only.
  const float lambdaB = family == LightFamily::Own ? b.lambdaOf(c.lanes, k0) : b.lambda;

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
    pairs[n++] = {SpectralLobe::Elastic, SpectralLobe::Elastic, a.lambda, b.lambda, Variant::kStandard};
  } else {
    if (a.bsdf->has(BsdfFlags::Fluorescent))
      pairs[n++] = {SpectralLobe::Fluorescent, SpectralLobe::Elastic, lambdaB, lambdaB, Variant::kOwn};
    if (b.bsdf->has(BsdfFlags::Fluorescent))
      pairs[n++] = {SpectralLobe::Elastic, SpectralLobe::Fluorescent, a.lambda, a.lambda, Variant::kOwn};
    if (c.bandwidth > 0.0f && std::abs(a.lambda - lambdaB) < c.bandwidth)
      pairs[n++] = {SpectralLobe::Elastic, SpectralLobe::Elastic, a.lambda, lambdaB, Variant::kMollified};
  }
  const LightEnd end = storedLightEnd(L, s);
  bool checked = false, unoccluded = false;
  for (int i = 0; i < n; ++i) {
    const Pair& p = pairs[i];
    // f at both ends for each lane: the shared family's elastic pair at every lane's own wavelength.
    float fA[kMaxLanes], fB[kMaxLanes];
    bool any = false;
    for (int k = k0; k < k1; ++k) {
      // An end that several lanes reach scatters each elastically at its own wavelength (shared).
      const float lambda = c.lanes.lambda[k];
      const bool lanesA = family == LightFamily::Shared && a.allLanes(c.lanes);
      const bool lanesB = family == LightFamily::Shared && b.allLanes(c.lanes);
      fA[k] = a.bsdf->eval(TransportMode::Importance, aWi, aWo, lanesA ? lambda : a.lambda, lanesA ? lambda : p.lambdaA, p.la);
      fB[k] = b.bsdf->eval(TransportMode::Radiance, bWi, bWo, lanesB ? lambda : p.lambdaB, lanesB ? lambda : lambdaB, p.lb);
      any = any || (fA[k] > 0.0f && fB[k] > 0.0f);
    }
    if (!any) continue;
    // The four densities next to the connection, for its lobes and wavelengths.
    const double pLightB = lightSide(c.scene, a, aPrev, b, p.la, a.lambda, p.lambdaA);
    const double pLightBNext = bNext.kind != Kind::Camera ? lightSide(c.scene, b, a, bNext, p.lb, p.lambdaB, lambdaB) : 0.0;
    const double pCamA = cameraSide(c.scene, b, bNext, a, p.lb, p.lambdaB, lambdaB);
    const double pCamAPrev = cameraSide(c.scene, a, b, aPrev, p.la, a.lambda, p.lambdaA);
    const MisSums sides = lightSum(L, s, pCamA, lightMultiplicity(L, s - 1, p.la, p.lambdaA), pCamAPrev) +
                          cameraSum(C, t, pLightB, cameraMultiplicity(C, t - 1, p.lb, p.lambdaB), pLightBNext);
    const MisSums here = joinMultiplicity(true, p.la, p.lb);
    MisSums own;
    (p.variant == Variant::kStandard ? own.shared : p.variant == Variant::kOwn ? own.own : own.mollified) = 1.0;
    const bool oneGroup = a.elasticBefore && b.elasticBefore && p.la == SpectralLobe::Elastic && p.lb == SpectralLobe::Elastic;
    const bool lanesKept = a.lanesKept && b.lanesKept;
    float weight[kMaxLanes];
    laneWeights(c, k0, k1, weight, [&](int k) { return fA[k] > 0.0f && fB[k] > 0.0f; }, [&](int k) {
      // The path's first wavelength: lane k's on a shared subpath, the own subpath's own.
      const MisFactors f = family == LightFamily::Shared
                               ? factors(c, L[0].light, a.lambdaOf(c.lanes, k), k, c.lanes.sensorPdf[k], oneGroup,
                                         lanesKept)
                               : factors(c, L[0].light, L[0].lambda, -1, c.lanes.sensorPdf[k], oneGroup, lanesKept,
                                         c.walk.lightFirst ? L[0].choicePdf : 0.0f);
      return weigh(c, s, t, p.variant, own, here + sides, f, [&](const MisFactors& g) {
        FullPath fp = layout(c, &L, s, C, t, end, g);
        fp.v[size_t(s - 1)].lobe = p.la;
        fp.v[size_t(s)].lobe = p.lb;
        fp.v[size_t(s)].pdfLight = pLightB;
        fp.v[size_t(s + 1)].pdfLight = pLightBNext;
        fp.v[size_t(s - 1)].pdfCam = pCamA;
        fp.v[size_t(s - 2)].pdfCam = pCamAPrev;
        const PathVertex& x1 = L[1];
        fp.specCam1 = s == 2 ? specCamera(x1, p.la, x1.lambda, p.lambdaA) : specCamera(x1, x1.lobe, x1.lambda, x1.lambdaNext);
        fp.specLightLast = t == 2 ? specLightLast(b, p.lb, p.lambdaB) : specLightLast(C[1], C[1].lobe, C[1].lambdaNext);
        return misWeight(fp, s, p.variant);
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
      const float value = a.beta[family == LightFamily::Shared ? k : 0] * fA[k] * G * fB[k] * b.beta[k] * kernel * laneScale;
      record(c, s, t, p.variant, k, value, weight[k]);
      out[k] += value * weight[k];
    }
  }
}

void connectToCamera(const Context& c, const std::vector<PathVertex>& L, LightFamily family, int s,
                     std::vector<Splat>& splats, VisibilityMemo* memo) {
  const PathVertex& a = L[size_t(s - 1)];
  if (a.kind == Kind::Infinite || !a.connectible()) return;
  const std::optional<Camera::Connection> conn = c.scene.camera.connect(a.p);
  if (!conn) return;
  PathVertex cam;
  cam.kind = Kind::Camera;
  cam.p = c.scene.camera.position();
  cam.deltaPosition = true;
  // The wavelength arriving at the pinhole: the light itself for s = 1, else the one a's sampled
  // spectral event sends towards the camera; with several lanes at a, each lane's own.
  const float lambda = s == 1 ? a.lambda : a.lambdaNext;
  const bool lanes = a.allLanes(c.lanes);
  const bool shared = family == LightFamily::Shared;
  const Variant variant = shared ? Variant::kStandard : Variant::kOwn;
  // The camera's density of a: its direction over the whole film (the sensor's density of the
  // wavelength arriving is a factor, mis_sums.h).
  const double pCamA = toAreaDensity(c.scene.camera.directionPdf(-conn->wi), cam, a);
  const LightEnd end = storedLightEnd(L, s);
  float value[kMaxLanes];
  bool any = false;
  MisSums here, own, sides;
  bool oneGroup = true;
  double pCamAPrev = 0.0;
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
    here = directLightMultiplicity(true);
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
      const float fa = lanes ? a.bsdf->eval(TransportMode::Importance, wi, wo, c.lanes.lambda[k], c.lanes.lambda[k], a.lobe)
                             : a.bsdf->eval(TransportMode::Importance, wi, wo, a.lambda, lambda, a.lobe);
      value[k] = a.beta[k] * fa * std::abs(wo.z) / a.spectralPdf;
      any = any || fa > 0.0f;
    }
    pCamAPrev = cameraSide(c.scene, a, cam, aPrev, a.lobe, a.lambda, lambda);
    here = lightTracingMultiplicity(true, a.spectralPdf);
    (shared ? own.shared : own.ownSplat) = double(a.spectralPdf) * a.spectralPdf;
    sides = lightSum(L, s, pCamA, lightMultiplicity(L, s - 1), pCamAPrev);
    oneGroup = a.elasticBefore && a.lobe == SpectralLobe::Elastic;
  }
  if (!any) return;
  const int k0 = a.firstLane(), k1 = a.endLane(c.lanes);
  float weight[kMaxLanes];
  laneWeights(c, k0, k1, weight, [&](int k) { return value[k] > 0.0f; }, [&](int k) {
    // A shared lane's wavelength is the sensor's lane k; an own subpath's arrives from the light.
    const bool lanesKept = s == 1 || a.lanesKept;
    const MisFactors mf = shared ? factors(c, L[0].light, a.lambdaOf(c.lanes, k), k, c.lanes.sensorPdf[k], oneGroup,
                                           lanesKept)
                                 : factors(c, L[0].light, L[0].lambda, -1, c.sensor.pdf(lambda), oneGroup, lanesKept,
                                           c.walk.lightFirst ? L[0].choicePdf : 0.0f);
    return weigh(c, s, 1, variant, own, here + sides, mf, [&](const MisFactors& g) {
      const std::vector<PathVertex> camOnly{cam};
      FullPath fp = layout(c, &L, s, camOnly, 1, end, g);
      const int last = s;
      fp.v[size_t(last - 1)].pdfCam = pCamA;
      if (s == 1) {
        fp.lightSeenByPinhole = true;
      } else {
        fp.v[size_t(last - 2)].pdfCam = pCamAPrev;
        const PathVertex& x1 = L[1];
        fp.specCam1 = s == 2 ? specCamera(x1, a.lobe, x1.lambda, lambda) : specCamera(x1, x1.lobe, x1.lambda, x1.lambdaNext);
        fp.specLightLast = a.spectralPdf;
      }
      return misWeight(fp, s, variant);
    });
  });
  if (std::none_of(weight + k0, weight + k1, [](float w) { return w > 0.0f; })) return;
  if (!(memo ? memo->get(s, 1, [&] { return visible(c, a, cam); }) : visible(c, a, cam))) return;
  // Importance W_j·cosθ/d² of the pixel, per light subpath (w·h of them per sample per pixel); a
  // shared lane's wavelength was the sensor's sample, one of n.
  const float perPath = 1.0f / (float(c.scene.camera.width()) * float(c.scene.camera.height()));
  Vec3 sum(0.0f), unweighted(0.0f);  // the lanes' XYZ
  for (int k = a.firstLane(); k < a.endLane(c.lanes); ++k) {
    if (!(value[k] > 0.0f)) continue;
    const float lambdaK = lanes ? c.lanes.lambda[k] : lambda;
    float sensorWeight = perPath;
    if (shared) sensorWeight /= float(c.lanes.n) * c.lanes.sensorPdf[k];
    const float v = value[k] * conn->importance * sensorWeight;
    // A shared lane's wavelength is the sensor's lane k (whose response is known).
    const Vec3 xyz = shared ? c.lanes.response[k] * v : Observer::cie1931().weight(lambdaK) * v;
    if (c.spectralSplats) splats.push_back({conn->pixel, xyz * weight[k], lambdaK, v * weight[k]});
    sum += xyz * weight[k];
    unweighted += xyz;
  }
  if (!c.spectralSplats) splats.push_back({conn->pixel, sum});
  if (c.log) c.log->push_back({conn->pixel, sum, unweighted, s, 1, uint8_t(variant)});
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
  for (int t = 2; t <= int(C.size()); ++t) {
    emitterHit(c, C, t, out, xyz);
    if (C[size_t(t - 1)].kind != Kind::Surface) continue;
    if (t - 1 <= maxDepth) {
      nextEvent(c, C, t, rng, out);
      if (!LO.empty()) connectLightVertex(c, LO, C, t, out);
    }
    for (int s = 2; s <= int(LS.size()) && (s - 1) + (t - 1) <= maxDepth; ++s)
      connect(c, LS, LightFamily::Shared, s, C, t, out, memo);
    for (int s = 2; s <= int(LO.size()) && (s - 1) + (t - 1) <= maxDepth; ++s)
      connect(c, LO, LightFamily::Own, s, C, t, out, memo);
  }
  // t = 1: light subpath vertices seen by the pinhole, splatted to their pixels.
  for (int s = 1; s <= int(LS.size()) && s - 1 <= maxDepth; ++s) connectToCamera(c, LS, LightFamily::Shared, s, splats, memo);
  for (int s = 1; s <= int(LO.size()) && s - 1 <= maxDepth; ++s) connectToCamera(c, LO, LightFamily::Own, s, splats, memo);
}

}  // namespace kasha::bdpt
