#include "integrators/bidirectional/photon_beam.h"

#include <cmath>

#include "integrators/bidirectional/connect_parts.h"
#include "integrators/bidirectional/path_media.h"
#include "integrators/bidirectional/subpath_mis.h"

namespace kasha::bidir {

void keepPhotonBeams(const std::vector<PathVertex>& L, bool own, const Scene& scene, const Strategies& st,
                     std::vector<PhotonBeam>& out) {
  if (!(st.merge.photonBeam > 0.0)) return;
  for (size_t m = 1; m < L.size(); ++m) {
    const PathVertex& v = L[m];
    const PathVertex& o = L[m - 1];
    // A flight through one homogeneous medium from a finite origin: where a collision's light-side
    // beam ratio is R_L/F_L (lightBeamRatio).
    if (!v.arrival.inMedia || v.arrival.crossesBoundary || o.kind == Kind::Infinite || v.kind == Kind::Infinite) continue;
    if (!(v.flightWeight > 0.0f) || !(v.beta[0] > 0.0f)) continue;
    PhotonBeam b;
    b.origin = o.p;
    const Vec3 span = v.p - o.p;
    b.length = glm::length(span);
    if (!(b.length > 0.0f) || !std::isfinite(b.length)) continue;
    b.w = span / b.length;
    b.medium = mediumToward(scene, o, b.w);
    if (b.medium < 0 || scene.media[size_t(b.medium)]->heterogeneous()) continue;
    // x_{m−1}'s density of w, from x_m's area density (pdfSA·G·F).
    b.directionPdf = v.pdfFwd / (double(toAreaDensity(1.0f, o, v)) *
                                 flightFactor(scene, TransportMode::Importance, v.arrival, v, v.lambda));
    if (!(b.directionPdf > 0.0) || !std::isfinite(b.directionPdf)) continue;
    b.originInMedium = o.inMedium();
    b.originDelta = o.deltaPosition;
    b.originMedium = o.medium;
    b.originNormal = o.n;
    LightVertex& r = b.vertex;
    // The flight ended the lanes in lane 0 (a flight through a medium does), and its weight T/p is the
    // collision's, not the beam's: the beam's throughput is what left x_{m−1}.
    r.beta[0] = v.beta[0] / v.flightWeight;
    r.lambda = v.lambda;
    r.lambda0 = L[0].lambda;
    r.ownStart = own ? L[0].choicePdf : 0.0f;
    r.pdfPrev = o.pdfFwd;
    r.light = int16_t(L[0].light);
    r.depth = uint8_t(m);
    r.lane = 0;
    r.flags = uint8_t((own ? LightVertex::kOwn : 0) | (v.elasticBefore ? LightVertex::kElasticBefore : 0) |
                      (o.joinable(false) ? LightVertex::kPrevConnectible : 0) |
                      (o.lobe == SpectralLobe::Fluorescent ? LightVertex::kPrevFluorescent : 0) |
                      (L[0].kind == Kind::Light ? LightVertex::kFiniteLight : 0) | LightVertex::kMedium |
                      LightVertex::kLightBeam);
    // keepLightVertices' sums, M_{m−1} + R_m, with x_{m−1}'s query-beam term apart.
    const int j = int(m) - 1;
    if (j == 0) {
      b.sumsFixed = lightMultiplicity(L, 0, st, false, false) + v.sums;
    } else {
      const MisSums without = lightMultiplicity(L, j, o.lobe, o.lambdaNext, st, false, false, 0.0, o.beamSine);
      b.sumsFixed = without + v.sums;
      b.sumsPerOriginBeam = lightMultiplicity(L, j, o.lobe, o.lambdaNext, st, false, false, 1.0, o.beamSine) + without * -1.0;
    }
    out.push_back(b);
  }
}

BeamPoint vertexAlong(const Scene& scene, const PhotonBeam& beam, float s) {
  BeamPoint point{beam.vertex};
  LightVertex& r = point.vertex;
  PathVertex x;  // the collision, as the densities see it
  x.kind = Kind::Medium;
  x.p = beam.origin + s * beam.w;
  x.medium = beam.medium;
  PathVertex o;  // the beam's origin, as the camera side reaches it
  o.kind = beam.originInMedium ? Kind::Medium : Kind::Surface;
  o.p = beam.origin;
  o.n = beam.originNormal;
  o.medium = beam.originMedium;
  o.deltaPosition = beam.originDelta;
  std::copy(&x.p.x, &x.p.x + 3, r.p);
  const Vec3 wi = scene.mediumBsdf(beam.medium, x.p).toLocal(-beam.w);
  std::copy(&wi.x, &wi.x + 3, r.wi);
  const SegmentDepth depth = depthThrough(scene, beam.medium, r.lambda, s);
  r.pdfFwd = float(beam.directionPdf * double(toAreaDensity(1.0f, o, x)) *
                   flightFactor(scene, TransportMode::Importance, depth, x, r.lambda));
  r.prevGeometry = float(toArea(scene, 1.0f, x, o) * flightFactor(scene, TransportMode::Radiance, depth, o, r.lambda));
  point.originCameraBeam = cameraBeamRatio(scene, depth, o, r.lambda);
  r.sums = beam.sumsFixed + beam.sumsPerOriginBeam * (point.originCameraBeam * point.originCameraBeam);
  return point;
}

}  // namespace kasha::bidir
