#include "integrators/bidirectional/connect_parts.h"

#include <algorithm>
#include <cmath>

#include "integrators/bidirectional/path_media.h"
#include "integrators/progressive_schedule.h"

namespace kasha::bidir {

Vec3 towards(const PathVertex& from, const PathVertex& to) {
  return to.kind == Kind::Infinite ? -to.dir : glm::normalize(to.p - from.p);
}

double toArea(const Scene& scene, float pdfSA, const PathVertex& at, const PathVertex& target) {
  if (target.kind == Kind::Camera || target.deltaPosition) return 0.0;
  if (target.kind == Kind::Infinite) return scene.lights[size_t(target.light)]->isDelta() ? 0.0 : pdfSA;
  return toAreaDensity(pdfSA, at, target);
}

double densityToward(const Scene& scene, const ScatterQuery& query, const PathVertex& at, const Vec3& wKnown,
                     const Vec3& wTarget, const PathVertex& target, const SegmentDepth& segment) {
  const bool radiance = query.mode == TransportMode::Radiance;
  const float known = radiance ? query.lambdaOut : query.lambdaIn;
  const float sampled = radiance ? query.lambdaIn : query.lambdaOut;
  const float pdf =
      at.bsdf->spectralPdf(query.mode, known, sampled, query.lobe) * at.bsdf->directionPdf(query, wKnown, wTarget);
  return toArea(scene, pdf, at, target) * flightFactor(scene, query.mode, segment, target, sampled);
}

LightEnd lightEnd(const Context& c, int light, const PathVertex& x0, const PathVertex& x1, const SegmentDepth& segment,
                  float lambda) {
  const Light& L = *c.scene.lights[size_t(light)];
  const Vec3 w = L.atInfinity() ? x0.dir : glm::normalize(x1.p - x0.p);
  float pdfPos = 0.0f, pdfDir = 0.0f;
  L.emissionPdfs(x0.p, x0.n, w, pdfPos, pdfDir);
  LightEnd e;
  e.pdf0 = L.atInfinity() ? pdfDir : pdfPos;
  if (x1.kind != Kind::Camera)
    e.pdf1 = (L.atInfinity() ? double(pdfPos) * x1.cosine(w) : toAreaDensity(pdfDir, x0, x1)) *
             flightFactor(c.scene, TransportMode::Importance, segment, x1, lambda);
  e.finite = !L.atInfinity();
  return e;
}

LightEnd storedLightEnd(const std::vector<PathVertex>& L, int s) {
  return {L[0].pdfFwd, s >= 2 ? double(L[1].pdfFwd) : 0.0, L[0].kind == Kind::Light};
}

MisFactors factors(const Context& c, int light, float lambda0, int lane, double sensorPdf, bool oneGroup,
                   bool lanesKept, float ownStart) {
  MisFactors f;
  f.sharedFamily = c.families.shared;
  f.ownFamily = c.families.independent;
  f.sensorPdf = sensorPdf;
  f.lambda0 = lambda0;
  f.oneGroup = oneGroup;
  if (lanesKept && f.ownFamily && c.walk.lightFirst) f.laneGain = c.lanes.n;
  const bool table = lane >= 0 && c.lanes.lights;
  if (table && oneGroup && !f.ownFamily) {
    f.cameraChoice = f.sharedChoice = c.lanes.lights->probability(size_t(light));
    return f;
  }
  f.cameraChoice = table ? c.lanes.lights->laneProbability(size_t(light), lane)
                         : c.scene.lightSelector->probability(size_t(light), lambda0);
  // The shared light subpath's choice: where it rides the merged subpath, that start's Q(l), exact
  // and a function of the light alone (light_first.h); else the camera family's.
  f.sharedChoice = f.ownFamily && c.walk.lightFirst ? c.walk.lightFirst->lightProbability(size_t(light)) : f.cameraChoice;
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
  }
  if (f.ownFamily && c.bandwidth > 0.0f) f.mollifyWidth = 1.0 / wavelengthKernel(0.0f, c.bandwidth);
  return f;
}

FullPath layout(const Context& c, const std::vector<PathVertex>* L, int s, const std::vector<PathVertex>& C, int t,
                const LightEnd& end, const MisFactors& f, bool connection) {
  FullPath fp;
  fp.families = c.families;
  fp.sensorPdf = f.sensorPdf;
  fp.laneGain = f.laneGain;
  fp.cameraChoice = f.cameraChoice;
  fp.sharedChoice = f.sharedChoice;
  fp.ownChoice = f.ownChoice;
  fp.mollifyWidth = f.mollifyWidth;
  fp.connections = c.walk.strategies.connections;
  fp.mergeEta = c.walk.strategies.merge;
  const int k = s + t - 1;
  fp.v.resize(size_t(k + 1));
  for (int i = 0; i < s; ++i) {
    const PathVertex& v = (*L)[size_t(i)];
    const bool ends = i == s - 1;
    fp.v[size_t(i)] = {v.pdfFwd, v.pdfRev, v.lobe, v.joinable(ends), v.inMedium(), mergeable(v, ends), v.cameraBeam, v.lightBeam,
                       v.beamSine};
  }
  for (int j = 0; j < t; ++j) {
    const PathVertex& v = C[size_t(j)];
    const bool ends = connection && j == t - 1;
    fp.v[size_t(k - j)] = {v.pdfRev, v.pdfFwd, v.lobe, v.joinable(ends), v.inMedium(), mergeable(v, ends), v.cameraBeam,
                           v.lightBeam, v.beamSine};
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

double specCamera(const PathVertex& x1, SpectralLobe lobe, float lambda0, float lambda1) {
  return x1.bsdf->spectralPdf(TransportMode::Radiance, lambda1, lambda0, lobe);
}

double specLightLast(const PathVertex& c1, SpectralLobe lobe, float lambdaIn) {
  return c1.bsdf->spectralPdf(TransportMode::Importance, lambdaIn, c1.lambda, lobe);
}

std::pair<int, float> ownJoinLane(const Context& c, const PathVertex& b) {
  if (!b.allLanes(c.lanes)) return {b.firstLane(), 1.0f};
  return {std::min(int(b.laneU * float(c.lanes.n)), c.lanes.n - 1), float(c.lanes.n)};
}

void laneZeroThroughMedia(const Context& c, float* value) {
  value[0] *= float(c.lanes.n);
  std::fill(value + 1, value + c.lanes.n, 0.0f);
}

float keptLaneScale(const Context& c, int laneA, int laneB) {
  return laneA >= 0 && laneB >= 0 && c.lanes.n > 1 ? 1.0f / float(c.lanes.n) : 1.0f;
}

Vec3 laneScale(const Context& c, int k) {
  return c.lanes.response[k] / (float(c.lanes.n) * c.lanes.pdf[k]);
}

void record(const Context& c, int s, int t, Variant v, int k, float value, float weight) {
  if (c.observer) recordXyz(c, s, t, v, k, laneScale(c, k) * value, weight);
}

void recordXyz(const Context& c, int s, int t, Variant v, int k, const Vec3& xyz, float weight) {
  c.observer->onContribution(k, c.pixel, xyz * weight);
  if (xyz.x != 0.0f || xyz.y != 0.0f || xyz.z != 0.0f)
    c.observer->onStrategy({c.pixel, xyz * weight, xyz, s, t, uint8_t(v)});
}

float emitted(const Context& c, const PathVertex& e, const PathVertex& next, float lambda) {
  if (e.kind == Kind::Infinite) return c.scene.environment()->Le(lambda, -e.dir);
  return static_cast<const AreaLight&>(*c.scene.lights[size_t(e.light)]).shape().emission->eval(lambda, e.n,
                                                                                                towards(e, next));
}

bool visible(const Context& c, const PathVertex& a, const PathVertex& b, float lambda, SegmentDepth* depth) {
  Vec3 o, w;
  float tMax = kInf;
  if (b.kind == Kind::Infinite) {
    w = -b.dir;
    o = offsetPoint(a.p, a.n, w);
  } else {
    const Vec3 d = b.p - a.p;
    const float dist = glm::length(d);
    w = d / dist;
    o = glm::dot(a.n, a.n) > 0.0f ? offsetPoint(a.p, a.n, w) : a.p;
    const float shorten = glm::dot(b.n, b.n) > 0.0f ? rayEpsilon(b.p) : 0.0f;
    tMax = dist * (1.0f - 1e-4f) - shorten - rayEpsilon(a.p);
  }
  if (!c.scene.hasMedia()) {
    ++c.counter.shadow;
    return !c.scene.accel->occluded(o, w, tMax);
  }
  float tr;
  SegmentDepth d;
  if (!segmentTransmittance(c.scene, o, w, tMax, mediumToward(c.scene, a, w), {&lambda, 1}, &tr, c.counter, &d)) return false;
  if (depth) *depth = d;
  return true;
}

namespace {

// The sums at the last vertex `end` of a subpath, before it `before` with `multiplicity`, given the
// join's densities towards them (pLast, pBefore).
MisSums endSum(const PathVertex& end, const PathVertex& before, const MisSums& multiplicity, double pLast,
               const MisSums& mLast, double pBefore) {
  return sideSum(end.sums, densityRatio(pBefore, before.pdfFwd), multiplicity, densityRatio(pLast, end.pdfFwd), mLast);
}

}  // namespace

MisSums cameraSum(const Context& c, const std::vector<PathVertex>& C, int t, double pLast, const MisSums& mLast,
                  double pBefore) {
  return endSum(C[size_t(t - 1)], C[size_t(t - 2)], cameraMultiplicity(C, t - 2, c.walk.strategies, false), pLast, mLast,
                pBefore);
}

MisSums lightSum(const Context& c, const std::vector<PathVertex>& L, int s, double pLast, const MisSums& mLast,
                 double pBefore) {
  return endSum(L[size_t(s - 1)], L[size_t(s - 2)], lightMultiplicity(L, s - 2, c.walk.strategies, false, false), pLast, mLast,
                pBefore);
}

MisSums lightEndSum(double pCam0, double pLight0) { return extend({}, densityRatio(pCam0, pLight0), hitMultiplicity()); }

}  // namespace kasha::bidir
