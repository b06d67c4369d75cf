#include "integrators/bidirectional/path_media.h"

#include <stdexcept>
#include <string>

namespace kasha::bidir {

int mediumToward(const Scene& scene, const PathVertex& v, const Vec3& w) {
  if (v.kind == PathVertex::Kind::Medium || v.shape < 0) return v.medium;
  Hit at;
  at.shape = uint32_t(v.shape);
  at.ng = v.n;
  return scene.mediumBeyond(at, w, v.medium);
}

double flightFactorInMedia(const Scene& scene, TransportMode mode, const SegmentDepth& d, const PathVertex& target,
                           float lambda) {
  const bool mixture = mode == TransportMode::Radiance && scene.hasFluorescentMedia();
  float rate = 1.0f, seekRate = 1.0f;
  if (target.kind == PathVertex::Kind::Medium) {
    // σ_t(λ) without a heterogeneous medium's density d(x): every strategy that makes the path
    // samples x by one free flight, from one side or the other, so d(x) is a factor of all of them.
    rate = seekRate = scene.media[size_t(target.medium)]->sigmaT(lambda);
    if (mixture) seekRate += scene.mediumScattering[size_t(target.medium)]->fluorescentWeight(mode, lambda);
  }
  return freeFlightDensity(mixture, d, rate, seekRate);
}

double cameraBeamRatio(const Scene& scene, const SegmentDepth& d, const PathVertex& target, float lambda) {
  if (target.kind != PathVertex::Kind::Medium || d.crossesBoundary || scene.media[size_t(target.medium)]->heterogeneous())
    return 0.0;
  const bool mixture = scene.hasFluorescentMedia();
  const double collide = flightFactorInMedia(scene, TransportMode::Radiance, d, target, lambda);
  return collide > 0.0 ? double(freeFlightDensity(mixture, d, 1.0f, 1.0f)) / collide : 0.0;
}

double lightBeamRatio(const Scene& scene, const SegmentDepth& d, const PathVertex& target, const PathVertex& origin,
                      float lambda) {
  if (target.kind != PathVertex::Kind::Medium || origin.kind == PathVertex::Kind::Infinite || d.crossesBoundary ||
      scene.media[size_t(target.medium)]->heterogeneous())
    return 0.0;
  return inverseSigmaT(scene, target.medium, lambda);
}

double inverseSigmaT(const Scene& scene, int medium, float lambda) {
  const float sigmaT = scene.media[size_t(medium)]->sigmaT(lambda);
  return sigmaT > 0.0f ? 1.0 / double(sigmaT) : 0.0;
}

bool sphereClearOfSurfaces(const Scene& scene, const Vec3& p, float r, RayCounter& counter) {
  constexpr float d = 0.57735027f;  // 1/√3
  static const Vec3 directions[14] = {{1, 0, 0},  {-1, 0, 0}, {0, 1, 0},  {0, -1, 0},  {0, 0, 1},  {0, 0, -1},
                                      {d, d, d},  {d, d, -d}, {d, -d, d}, {d, -d, -d}, {-d, d, d}, {-d, d, -d},
                                      {-d, -d, d}, {-d, -d, -d}};
  for (const Vec3& w : directions) {
    ++counter.shadow;
    if (scene.accel->occluded(p, w, r)) return false;
  }
  return true;
}

void requireBidirectionalMedia(const RenderSettings& settings, const std::string& integrator) {
  if (integrator == "bdpt" && settings.bdpt.mollify)
    throw std::invalid_argument("bdpt: render/bdpt/mollify: not supported in scenes with media");
}

}  // namespace kasha::bidir
