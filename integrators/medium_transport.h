#pragma once
// Rays through participating media (docs/media.md §3), for every integrator that transports light
// in them: free flights sampled by optical depth at the wavelength of the path's hero lane (lane 0),
// and transmittance along connections, both across index-matched boundaries (shapes that only
// separate media), switching media as the shapes' MediumInterfaces say.
#include <algorithm>
#include <cmath>
#include <optional>
#include <span>

#include "core/light.h"
#include "core/sampler.h"
#include "integrators/integrator.h"
#include "integrators/wavelength_lanes.h"
#include "scene/scene.h"

namespace kasha {

// Spectral MIS of the lanes of a path whose free flights were drawn at lane 0's wavelength (hero
// wavelength sampling, Wilkie et al. 2014; docs/media.md eq. 7): r_k is the ratio p_k/p_0 of the
// densities with which the path's free flights since the lanes were drawn would have been sampled
// had lane k been the hero. Lane 0 is a uniform choice among lanes drawn at symmetric strata, so
// lane k's contribution f_k/p_0 divided by the mean of the r_j is the balance heuristic over the
// N hero choices: unbiased for every lane. Every r_k stays 1 where σ_t does not depend on λ, and
// in scenes without media.
struct LaneRatios {
  int n = 0;
  float r[kMaxLanes];
  void reset(int lanes);
  // 1/((1/N)·Σ_k r_k): what every lane's contribution is multiplied by.
  float misWeight() const;
};

// The optical depths of a segment at one wavelength: under the analog rate σ_t, and under the
// camera paths' source-seeking rate σ_t + A_fl (docs/media.md eq. 6b).
struct SegmentDepth {
  float analog = 0.0f, seeking = 0.0f;
  // Whether the segment runs through a medium at all: a property of its geometry and the scene's
  // media, the same at every wavelength (where the bidirectional engine's lanes end, docs/media.md §5).
  bool inMedia = false;
  // Whether it crosses an index-matched boundary (from one medium into the next): a camera side's
  // query beam ends at the first (docs/media-beams.md).
  bool crossesBoundary = false;
};

// The optical depths at lambda over `length` through `medium` (for a heterogeneous one, the caller's
// integral of its density along the segment in place of the length): σ_t·length and, the camera
// paths' source-seeking rate, (σ_t + A_fl)·length (docs/media.md eq. 6b).
SegmentDepth depthThrough(const Scene& scene, int medium, float lambda, float length);

// What a ray from a vertex reaches through the media: a collision in a medium, a surface, or
// nothing.
struct FreeFlight {
  std::optional<Hit> hit;  // the surface reached (never an index-matched boundary) if no collision
  bool collided = false;   // a collision at p in `medium`
  Vec3 p{0.0f};
  int medium = -1;         // the medium collided in, or the ray's on arriving at `hit` or escaping
  // Per lane: the free flight's transmittance (times σ_t at a collision is not included) over lane
  // 0's density of the event, T_k/p_0, and the ratio of the densities, p_k/p_0 (LaneRatios). Both
  // 1 if the ray crossed no medium.
  float weight[kMaxLanes];
  float ratio[kMaxLanes];
  // Lane 0's optical depths over the flight: with freeFlightDensity, its density at lane 0, and
  // a camera path's density of the same segment (the seeking depth is tracked on light paths too, in
  // scenes with a fluorescent medium). Exact in homogeneous media; in heterogeneous ones the
  // majorant's, or with estimateDepth an estimate of the true one.
  SegmentDepth depth;
};

// The density with which a free flight over optical depths `d` ends where it does (docs/media.md
// eqs. 6, 6b): at a collision, with the rates there (`rate` σ_t, `seekRate` σ_t + A_fl), or past the
// media (both 1: the probability of passing). `mixture`: a camera path's flight in a scene with a
// fluorescent medium, the ½/½ mixture of both rates.
inline float freeFlightDensity(bool mixture, const SegmentDepth& d, float rate, float seekRate) {
  const float analog = std::exp(-d.analog) * rate;
  return mixture ? 0.5f * (analog + std::exp(-d.seeking) * seekRate) : analog;
}

// Follows `ray` from a vertex in `medium` (−1: vacuum) with the lanes' wavelengths, colliding where
// the optical depth at lambda[0] reaches −ln(1 − u) (docs/media.md eq. 6), by delta tracking in
// heterogeneous media (eq. 8). Camera paths (Radiance) in a scene with a fluorescent medium draw
// it, half of the time, with the fluorescent source rate A_fl(λ_0) added to σ_t (eq. 6b): a medium
// that fluoresces at λ_o without absorbing it (a Stokes shift) would otherwise never be collided
// with at λ_o. In a scene without media this is one intersection (inline: the integrators' hot
// loop), and `weight` and `ratio` are left unset: without media there is nothing to weigh.
// With estimateDepth, FreeFlight::depth counts heterogeneous media by a deterministic estimate of
// their optical depth (a midpoint rule over the density) instead of the majorant's.
FreeFlight traceFreeFlightThroughMedia(const Scene& scene, Ray ray, int medium, std::span<const float> lambda, float u,
                                       TransportMode mode, RayCounter& counter, bool estimateDepth = false);
inline FreeFlight traceFreeFlight(const Scene& scene, const Ray& ray, int medium, std::span<const float> lambda, float u,
                                  TransportMode mode, RayCounter& counter, bool estimateDepth = false) {
  if (scene.hasMedia()) return traceFreeFlightThroughMedia(scene, ray, medium, lambda, u, mode, counter, estimateDepth);
  FreeFlight f;
  f.hit = scene.accel->intersect(ray);
  ++counter.closest;
  return f;
}

// The transmittance exp(−τ(λ_k)) of every lane along the segment from `origin` (in `medium`) in
// direction d up to distance tMax, across index-matched boundaries; false (and tr unset) if a
// surface blocks the segment. With `depths`, also each lane's optical depths, analog and
// source-seeking, what freeFlightDensity needs (exact in homogeneous media, estimated as
// traceFreeFlight's estimateDepth in heterogeneous ones). In a scene without media, one occlusion
// query (inline).
bool segmentTransmittanceThroughMedia(const Scene& scene, Vec3 origin, const Vec3& d, float tMax, int medium,
                                      std::span<const float> lambda, float* tr, RayCounter& counter,
                                      SegmentDepth* depths = nullptr);
inline bool segmentTransmittance(const Scene& scene, const Vec3& origin, const Vec3& d, float tMax, int medium,
                                 std::span<const float> lambda, float* tr, RayCounter& counter,
                                 SegmentDepth* depths = nullptr) {
  if (scene.hasMedia()) return segmentTransmittanceThroughMedia(scene, origin, d, tMax, medium, lambda, tr, counter, depths);
  ++counter.shadow;
  if (scene.accel->occluded(origin, d, tMax)) return false;
  std::fill(tr, tr + lambda.size(), 1.0f);
  if (depths) std::fill(depths, depths + lambda.size(), SegmentDepth{});
  return true;
}

// The medium around a path vertex: the one the path arrived in, and whether the vertex is on a
// surface (whose MediumInterface decides which medium a direction leaves into) or a point inside
// that medium.
struct VertexMedium {
  int medium = -1;
  bool onSurface = true;
  int leaving(const Scene& scene, const Hit& hit, const Vec3& d) const {
    return onSurface ? scene.mediumBeyond(hit, d, medium) : medium;
  }
};

// The shadow ray of next-event estimation: the transmittance of every lane from vertex `hit` (a
// surface hit, or a medium point with ng = 0) to the light point of `ls`; false if a surface blocks it.
inline bool lightTransmittance(const Scene& scene, const Hit& hit, VertexMedium where, const LightSample& ls,
                               std::span<const float> lambda, float* tr, RayCounter& counter) {
  const Vec3 origin = offsetPoint(hit.p, hit.ng, ls.wi);
  const float tMax = std::isinf(ls.dist) ? kInf : ls.dist * (1.0f - 1e-4f) - rayEpsilon(hit.p);
  const int medium = scene.hasMedia() ? where.leaving(scene, hit, ls.wi) : -1;
  return segmentTransmittance(scene, origin, ls.wi, tMax, medium, lambda, tr, counter);
}

// The uniform of the free flight from vertex `depth` of a path whose dimensions start at
// firstDimension: from a region of the sampler's dimensions of its own, so that the vertex blocks
// of docs/sampler.md keep their layout. Leaves the sampler at vertex `depth`'s block.
float freeFlightUniform(Sampler& rng, uint32_t firstDimension, int depth);

}  // namespace kasha
