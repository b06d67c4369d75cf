#pragma once
// The photon pass: light subpaths in Importance mode that carry wavelength lanes as the light
// tracer's do (light_start_lanes.h: lanes at the strata of the light-start strategy, the light
// symmetric in them; at each vertex one spectral event for every lane, wavelength_lanes.h: each lane
// keeps its wavelength through the elastic lobe, a fluorescent event gives fresh lanes ∝ e, Jung18
// eq. 6, and a direction that depends on λ keeps one lane), through media by the light tracer's free
// flights. Each photon holds the lanes that arrive at its vertex.
#include <cstdint>
#include <vector>

#include "core/sampler.h"
#include "core/wavelength_density.h"
#include "integrators/integrator.h"
#include "integrators/photon_mapping/photon.h"

namespace kasha {

struct PhotonTracing {
  size_t paths = 0;      // light subpaths to trace (the photons "emitted" in the estimate)
  int lanes = 1;         // wavelength lanes per subpath
  int maxDepth = 0;      // photons are stored at vertices firstStoredDepth..maxDepth
  int firstStoredDepth = 1;  // 2 when next-event estimation counts the light arriving straight from a light
  int rrDepth = 3;       // Russian roulette from this vertex on
  uint64_t memoryLimit = 0;  // bytes: stored photons × kBytesPerPhoton must stay within it
  const WavelengthDensity* wavelengths = nullptr;  // the light-start strategy's density
  SamplerKind sampler = SamplerKind::Sobol;        // path j is sample j of the pass's sequence
};

// The photons of one pass: at surface vertices and at collisions in media (the volume photon map).
struct PassPhotons {
  std::vector<Photon> surface, volume;
};

// Traces the subpaths and returns a photon for every vertex from firstStoredDepth on that has a
// non-specular lobe (every collision in a medium has) and a lane of positive power (only those
// lanes are kept, kPhotonLanes to a photon). Path j draws from its own stream of `seed`, and the
// photons of each map come in path order, so the result does not depend on the number of threads.
// Throws MemoryLimitError as soon as the photons stored so far exceed the memory limit.
PassPhotons tracePhotons(const Scene& scene, const PhotonTracing& settings, uint64_t seed, RayCounter& counter);

}  // namespace kasha
