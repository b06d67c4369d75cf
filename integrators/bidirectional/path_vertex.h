#pragma once
// A vertex of a BDPT subpath (camera or light). Densities follow docs/bdpt-mis.md: pdfFwd is the
// density with which the vertex's own subpath produced it, pdfRev the density with which the
// other subpath would have; both include the spectral event at the neighbour that sampled it
// (lobe probability, and the per-nm density when that lobe is fluorescent), and are per unit
// area (per steradian for a light at infinity). The light vertex's pdfFwd is its position's alone
// and the first camera hit's the camera direction's alone: the light choice and the wavelength
// densities are factors of each strategy (mis_sums.h), applied once the path is known.
#include <optional>

#include "core/math.h"
#include "integrators/bidirectional/mis_sums.h"
#include "integrators/medium_transport.h"
#include "integrators/lane_light_choice.h"
#include "integrators/wavelength_lanes.h"
#include "materials/bsdf.h"

namespace kasha::bidir {

// The wavelength lanes of a subpath (docs/bdpt-mis.md §10): the camera sample's n wavelengths at the
// strata of the sensor density (SampledLanes, pdf the sensor's p(λ_k)), shared by the shared-family
// light subpath; an own-family light subpath has one lane, its own wavelength, and no use for the
// rest.
struct Lanes : SampledLanes {
  Vec3 response[kMaxLanes];    // the sensor's XYZ response W(λ_k)
  // p_light(λ_k), the light-start density (weights of the own family against each lane; only where
  // both run with more than one lane).
  float lightPdf[kMaxLanes];
  const LaneLightTable* lights = nullptr;  // the lights' powers at the lanes (more than one lane)
  // The merged light subpath's own start density at the lanes (docs/bdpt-mis.md §11):
  // Q(l)·p_l(λ_k) at k·lights + l (more than one lane, where the unified estimator merges).
  const float* ownStart = nullptr;
};

struct PathVertex {
  // Medium: a collision inside a participating medium (docs/media.md §5).
  enum class Kind : uint8_t { Camera, Light, Surface, Medium, Infinite } kind = Kind::Surface;
  Vec3 p{0.0f};
  Vec3 n{0.0f};            // geometric normal; zero for the camera, point/spot lights and medium points
  Vec3 dir{0.0f};          // Infinite vertices: the direction light travels
  std::optional<Bsdf> bsdf;  // surface and medium vertices: the scattering function there
  int light = -1;          // index of the light this vertex lies on (light vertex, or an emitter hit)
  // Media (scenes with media only): a medium vertex's medium; any other vertex's, the medium around
  // it as its subpath found it (arrived in, or the camera's and the light's own); and the shape a
  // surface or area-light vertex lies on, whose MediumInterface says which medium a direction
  // leaves into (mediumToward).
  int medium = -1;
  int shape = -1;
  // The optical depths, at lane 0's wavelength (this vertex's `lambda` wherever the segment runs
  // through a medium: the lanes end there), of the segment its subpath reached it along: what the
  // free-flight densities of that segment need (medium_transport.h).
  SegmentDepth arrival;
  // A collision whose merge sphere (radius MergeEta::volumeRadius) meets no surface: only there do
  // merges in media happen (docs/media.md §6).
  bool sphereInMedium = true;
  // A collision in a homogeneous medium: the camera side's R_C/F_C of it (FullVertex::cameraBeam,
  // cameraBeamRatio) over the segment it reaches it along: on a camera subpath its arrival, on a
  // light subpath the next vertex's (set when that one arrives); connections recompute it for the
  // segment they join.
  float cameraBeam = 0.0f;
  // The light side's R_L/F_L of it (FullVertex::lightBeam, lightBeamRatio) over the segment the light
  // side reaches it along: on a light subpath its arrival, on a camera subpath the next vertex's;
  // connections recompute it for the camera end they join.
  float lightBeam = 0.0f;
  // A collision's sin θ between its two segments (|u × v| of their directions), set with lightBeam
  // once both neighbours are known: a photon beam crossing a query beam at x has density ∝ sin θ
  // (docs/media-beams.md eq. B4); connections and merges recompute it at their ends.
  float beamSine = 0.0f;
  // The free flight's weight T/p at lane 0 that the subpath's throughput took on arriving here (1
  // without media): a query beam along the same segment replaces it (vcm, docs/media-beams.md).
  float flightWeight = 1.0f;
  // Subpath throughput of each lane up to this vertex, its own scattering excluded; 0 for a lane
  // that ended.
  float beta[kMaxLanes] = {};
  // The lanes that reach this vertex: -1 every lane of the subpath, each at its own wavelength; else
  // only this one (at `lambda`), its throughput times n: a vertex whose sampling depends on the
  // wavelength, and a flight through a medium, end the lanes in lane 0 (docs/bdpt-mis.md §10).
  int8_t lane = -1;
  // Where this vertex ended the lanes (on arrival), the throughput of every lane that arrived: a
  // merge here needs only the light arriving, which every lane knows (docs/bdpt-mis.md §12).
  bool lanesEndHere = false;
  float betaArriving[kMaxLanes] = {};
  // The uniform number drawn where several lanes arrive: it picks the lane an own-family join at
  // this vertex serves (docs/bdpt-mis.md §10).
  float laneU = 0.0f;
  // The subpath's wavelength at this vertex: arriving from the previous light-subpath vertex, or
  // leaving towards the previous camera-subpath vertex. While several lanes reach a vertex, the
  // wavelength of its densities: a lane at which it scatters (their densities are those of every
  // lane that scatters there, docs/bdpt-mis.md §10).
  float lambda = 0.0f;
  // The spectral event sampled here (valid when `eventSampled`): it extends the subpath, and
  // next-event estimation (camera side) or the camera connection (light side) reuse it.
  bool eventSampled = false;
  SpectralLobe lobe = SpectralLobe::Elastic;
  float lambdaNext = 0.0f;  // wavelength of the segment towards the next subpath vertex
  float spectralPdf = 0.0f; // density of that spectral event in the subpath's mode
  bool specular = false;
  float pdfFwd = 0.0f, pdfRev = 0.0f;
  bool deltaPosition = false;  // point and spot lights, the pinhole
  // The orthographic camera: its rays share one direction, so the density of the next vertex is
  // per unit area across them, times |cos| there (no 1/d², as from a light at infinity).
  bool parallelRays = false;
  // A light subpath's first vertex: the probability with which its light was chosen (and, on an
  // own-family subpath, its wavelength with it: p_light(λ_0)·p(light | λ_0)).
  float choicePdf = 0.0f;
  // Recursive MIS (docs/bdpt-mis.md §9): the running sum over the strategies with at least two
  // fewer vertices on this subpath's side, and whether every interior vertex before this one on
  // the subpath scattered elastically.
  MisSums sums;
  bool elasticBefore = true;
  // Whether no vertex of the subpath up to this one (included) makes sampling depend on λ, and no
  // flight up to it ran through a medium: the wavelength lanes reach it all (docs/bdpt-mis.md §10).
  bool lanesKept = true;
  // Whether every vertex between this one and the subpath's start is specular: on a camera subpath,
  // this is the path's first gather vertex (MergeEta, docs/bdpt-mis.md §12).
  bool gather = true;

  bool onSurface() const { return kind == Kind::Surface; }
  // Whether the vertex scatters (a surface or a medium point), as opposed to a path's end.
  bool scatters() const { return kind == Kind::Surface || kind == Kind::Medium; }
  bool inMedium() const { return kind == Kind::Medium; }
  // |cos θ| of direction w with the normal; 1 at a vertex without one (a medium point, a point light).
  float cosine(const Vec3& w) const { return glm::dot(n, n) > 0.0f ? std::abs(glm::dot(n, w)) : 1.0f; }
  // Whether several lanes reach this vertex (each at its own wavelength).
  bool allLanes(const Lanes& lanes) const { return lane < 0 && lanes.n > 1; }
  // The lanes that reach this vertex, [first, last).
  int firstLane() const { return lane < 0 ? 0 : lane; }
  int endLane(const Lanes& lanes) const { return lane < 0 ? lanes.n : lane + 1; }
  // Lane k's wavelength here (k one of the lanes that reach it).
  float lambdaOf(const Lanes& lanes, int k) const { return allLanes(lanes) ? lanes.lambda[k] : lambda; }
  // Whether a connection can end here: lights, the camera, scattering points with a smooth lobe.
  bool connectible() const { return !scatters() || !bsdf->has(BsdfFlags::DeltaDirection); }
  // Whether another strategy could end a connection or a merge here on the path being weighed
  // (docs/bdpt-mis.md §9). Where the path `ends` a connection or a merge here, as connectible.
  // Where it goes on through this vertex's own sampled event, not if that event was a delta, even
  // at a point with smooth lobes too (an opacity mask's pass-through, BsdfFlags::DeltaLobe): a
  // connection cannot make a path through a delta. Per event, as pbrt-v4's Vertex::delta.
  bool joinable(bool ends) const { return ends ? connectible() : !scatters() || !specular; }
};

// Area density at `to` of a solid-angle density at `from` (|cos| at `to` / d²); a vertex without a
// normal (point light, camera) or at infinity gets no cosine (and no distance for infinity). From
// parallel rays (the orthographic camera) the density is per unit area across them: |cos| at `to`
// alone.
inline float toAreaDensity(float pdfSolidAngle, const PathVertex& from, const PathVertex& to) {
  if (to.kind == PathVertex::Kind::Infinite) return pdfSolidAngle;
  if (from.kind == PathVertex::Kind::Infinite) return pdfSolidAngle;  // handled by the caller
  const Vec3 d = to.p - from.p;
  const float dist2 = glm::dot(d, d);
  if (!(dist2 > 0.0f)) return 0.0f;
  const float c = glm::dot(to.n, to.n) > 0.0f ? std::abs(glm::dot(to.n, d)) / std::sqrt(dist2) : 1.0f;
  return from.parallelRays ? pdfSolidAngle * c : pdfSolidAngle * c / dist2;
}

}  // namespace kasha::bidir
