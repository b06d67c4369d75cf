#pragma once
// The light subpaths of one vertex-merging pass (docs/bdpt-mis.md §12): N subpaths at the pass's
// lanes, traced as BDPT's (one subpath read as both wavelength families where the scene
// fluoresces), whose mergeable vertices are kept as LightVertex records.
#include <cstdint>
#include <vector>

#include "core/sampler.h"
#include "integrators/bidirectional/light_vertex.h"
#include "integrators/bidirectional/photon_beam.h"
#include "integrators/bidirectional/subpaths.h"
#include "integrators/point_map.h"

namespace kasha {

// A pass's light vertices with their k-d trees.
using LightVertexMap = PointMap<bidir::LightVertex>;
extern template class PointMap<bidir::LightVertex>;

struct LightVertexTracing {
  size_t paths = 0;          // light subpaths to trace (N)
  SamplerKind sampler = SamplerKind::Sobol;  // subpath j is sample j of the pass's sequence
  uint64_t memoryLimit = 0;  // bytes: kept vertices × kBytesPerLightVertex must stay within it
  // Without ws.lightFirst, trace an own-family subpath besides the shared one (scenes with media,
  // where the two families cannot share one walk: docs/media.md §5).
  bool ownFamily = false;
};

// Memory per kept light vertex: the record and its share of the k-d tree (point_map.h), or two
// records while the pass's per-chunk buffers are copied into one array.
inline constexpr size_t kBytesPerLightVertex = 2 * bidir::kLightVertexBytes;

// Traces the subpaths (ws.lightFirst set: the merged subpath of both families; else the shared
// family's, and the own family's where t.ownFamily) at `lanes` and returns their kept vertices in subpath order, whatever the number of
// threads; subpath j draws from stream j of `seed`. Throws MemoryLimitError as soon as the vertices
// kept so far exceed the memory limit. With `beams`, where the walk has photon beams, their flights
// through media too (keepPhotonBeams), in subpath order, within the memory the vertices leave.
std::vector<bidir::LightVertex> traceLightVertices(const Scene& scene, const bidir::Lanes& lanes,
                                                  const bidir::WalkSettings& ws, const LightVertexTracing& t,
                                                  uint64_t seed, RayCounter& counter,
                                                  std::vector<bidir::PhotonBeam>* beams = nullptr);

}  // namespace kasha
