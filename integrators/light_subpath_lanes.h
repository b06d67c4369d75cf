#pragma once
// Light subpaths that carry wavelength lanes (the light tracer's and the photon pass's,
// docs/wavelength-sampling.md "Hero wavelengths"): the start — N lanes at the strata of the
// light-start density, a light chosen symmetrically in them (LaneLightTable), and one emission
// sample, whose geometry does not depend on λ, serving every lane — and the step through a vertex
// once its spectral event (sampleLaneEvent, Importance mode) is known.
#include <optional>

#include "core/light.h"
#include "core/sampler.h"
#include "core/wavelength_density.h"
#include "integrators/medium_transport.h"
#include "integrators/wavelength_lanes.h"
#include "scene/scene.h"

namespace kasha {

// The lanes of a light subpath segment: wavelength and throughput (flux per subpath) of each.
using LightLanes = PathLanes<float>;

struct LightStartLanes {
  LightLanes lanes;  // lanes.n = 0 if the start failed (no light emits at the lanes, or no emission sample)
  const Light* light = nullptr;
  size_t lightIndex = 0;  // light's index in Scene::lights
  EmissionSample es;
  float start[kMaxLanes];  // 1/(N·p(λ_j)·P(light)): lane j's weight, the balance heuristic over the lanes;
                           // lanes.beta[j] = L_e(λ_j)·start_j·cos/(p_pos·p_dir)
};

// The light's point of a started subpath as a path vertex (docs/media.md §3): on an area light's
// shape (whose MediumInterface, if any, names the medium on each side), else a point in the light's
// medium.
struct LightOrigin {
  Hit hit;
  VertexMedium where;
};
LightOrigin lightOrigin(const Scene& scene, const LightStartLanes& start);

// A vertex of a light subpath reached through the media (docs/media.md §3): a surface, or a point
// in a medium (no shape, ng = 0: offsetPoint leaves it where it is) whose Bsdf is the medium's
// collision kernel (BsdfFlags::Volume).
struct LightSubpathVertex {
  Hit hit;
  VertexMedium where;
  Bsdf bsdf;
  float mis;  // every contribution's share of the lanes' spectral MIS of free flights (LaneRatios); 1 without media
};

// Vertex `depth` (≥ 1) of a light subpath whose dimensions start at firstDimension: the free flight
// along `ray` from the previous vertex in `medium` (Importance mode, its uniform from
// freeFlightUniform), whose per-lane weights T_k/p_0 multiply the lanes' beta and whose density
// ratios p_k/p_0 multiply `ratios`. Leaves the sampler at the vertex's block; nullopt if the ray
// leaves the scene.
std::optional<LightSubpathVertex> nextLightVertex(const Scene& scene, const Ray& ray, int medium, LightLanes& lanes,
                                                  LaneRatios& ratios, Sampler& rng, uint32_t firstDimension, int depth,
                                                  RayCounter& counter);

// Lane j at the stratum (uLambda + j/n) of `density`'s inverse CDF, the light from uLight, the
// emission's point and direction from uPos and uDir.
LightStartLanes startLightLanes(const Scene& scene, const WavelengthDensity& density, int n, float uLambda, float uLight,
                                Vec2 uPos, Vec2 uDir);

// Continues `lanes` (those arriving at the vertex, along -wi in the Bsdf's frame) through the
// vertex's spectral event e: the direction at lane 0's wavelengths from the next two dimensions of
// rng (every lane has the same direction density), each new lane's weight (laneWeight), and, with
// `roulette`, Russian roulette against the start's throughput beta0 from one more dimension. Returns
// the new direction in the world frame, or nullopt if the subpath ends.
std::optional<Vec3> scatterLightLanes(const Bsdf& bsdf, const Vec3& wi, const LaneEvent& e, LightLanes& lanes,
                                      bool roulette, float beta0, Sampler& rng);

}  // namespace kasha
