#pragma once
// The media around the bidirectional engine's vertices (docs/media.md §5–6): which medium a
// direction leaves a vertex into, the free-flight factor of a vertex's area density (exactly 1 in a
// scene without media), whether a merge's sphere stays inside its medium, and what the engine
// refuses in media.
#include <string>

#include "integrators/bidirectional/path_vertex.h"
#include "scene/render_settings.h"
#include "scene/scene.h"

namespace kasha::bidir {

// The medium a ray from v in world direction w travels in: a medium vertex's own; from a shape with
// a MediumInterface the side w points into; else the medium around v.
int mediumToward(const Scene& scene, const PathVertex& v, const Vec3& w);

// The factor a free flight drawn in `mode` at wavelength lambda, over a segment of optical depths d,
// contributes to the area density of `target` at its end (docs/media.md eq. 9): the density per
// unit length of colliding there (σ_t·T, or the camera mixture's, eq. 6b) at a medium vertex, the
// probability of passing the media at any other (a surface, a light, the camera, infinity).
// Inline: every density of every scene asks, and in one without media the answer is 1.
double flightFactorInMedia(const Scene& scene, TransportMode mode, const SegmentDepth& d, const PathVertex& target,
                           float lambda);
inline double flightFactor(const Scene& scene, TransportMode mode, const SegmentDepth& d, const PathVertex& target,
                           float lambda) {
  return scene.hasMedia() ? flightFactorInMedia(scene, mode, d, target, lambda) : 1.0;
}

// R_C/F_C at `target` (docs/media-beams.md eq. B1): the probability that a camera side's free flight
// over a segment of optical depths d, at wavelength lambda, passes `target` over its density of
// colliding there (flightFactor's), where `target` is a collision in a homogeneous medium that the
// segment reaches without crossing a boundary; 0 at any other vertex, and in a heterogeneous medium,
// whose density d(x) flightFactor leaves out.
double cameraBeamRatio(const Scene& scene, const SegmentDepth& d, const PathVertex& target, float lambda);

// R_L/F_L at `target` (docs/media-beams.md eq. B4): the same for a light side's flight from `origin`,
// analog (F_L = σ_t·e^{−τ}, R_L = e^{−τ}), so inverseSigmaT at a collision in a homogeneous medium
// that the segment reaches without crossing a boundary from a finite origin (a flight from a light
// at infinity is no photon beam: keepPhotonBeams); 0 at any other vertex.
double lightBeamRatio(const Scene& scene, const SegmentDepth& d, const PathVertex& target, const PathVertex& origin,
                      float lambda);
// sin θ between the segments from x to a and from x to b (0 where one has no length).
inline float crossingSine(const Vec3& x, const Vec3& a, const Vec3& b) {
  const Vec3 u = a - x, v = b - x;
  const float uu = glm::dot(u, u), vv = glm::dot(v, v);
  if (!(uu > 0.0f && vv > 0.0f)) return 0.0f;
  return std::min(1.0f, glm::length(glm::cross(u, v)) / std::sqrt(uu * vv));
}

// 1/σ_t(λ) of a homogeneous medium (0 where σ_t is).
double inverseSigmaT(const Scene& scene, int medium, float lambda);

// Whether the sphere of radius r around p meets no surface, by 14 segments from p (the axes and the
// diagonals): a merge's sphere in a medium (docs/media.md §6) that reaches out of it would count the
// light vertices of a volume it does not fill, a bias of the order of r/(the medium's thickness). A
// deterministic function of p, so that the merges' weights and the merges agree.
bool sphereClearOfSurfaces(const Scene& scene, const Vec3& p, float r, RayCounter& counter);

// Throws std::invalid_argument where the bidirectional engine cannot transport media with these
// settings: spectral mollification (its connections join two wavelengths, each with flights of its
// own density).
void requireBidirectionalMedia(const RenderSettings& settings, const std::string& integrator);

}  // namespace kasha::bidir
