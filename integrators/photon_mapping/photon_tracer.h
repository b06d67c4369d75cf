#pragma once
// The photon pass: light subpaths in Importance mode, started with the joint (light, wavelength)
// density of LightSelector (λ from the light-start strategy), each photon keeping its own wavelength, which the material's spectral
// stage changes at fluorescent events (Jung18 eq. 6: P_l, then λ_o ∝ e).
#include <cstdint>
#include <vector>

#include "core/sampler.h"
#include "core/wavelength_density.h"
#include "integrators/integrator.h"
#include "integrators/photon_mapping/photon.h"

namespace kasha {

struct PhotonTracing {
  size_t paths = 0;      // light subpaths to trace (the photons "emitted" in the estimate)
  int maxDepth = 0;      // photons are stored at vertices firstStoredDepth..maxDepth
  int firstStoredDepth = 1;  // 2 when next-event estimation counts the light arriving straight from a light
  int rrDepth = 3;       // Russian roulette from this vertex on
  uint64_t memoryLimit = 0;  // bytes: stored photons × kBytesPerPhoton must stay within it
  const WavelengthDensity* wavelengths = nullptr;  // the light-start strategy's density
  SamplerKind sampler = SamplerKind::Sobol;        // path j is sample j of the pass's sequence
};

// Traces the subpaths and returns a photon for every vertex from firstStoredDepth on that has a
// non-specular lobe. Path j
// draws from its own stream of `seed`, and the photons come in path order, so the result does not
// depend on the number of threads. Throws MemoryLimitError as soon as the photons stored so far
// exceed the memory limit.
std::vector<Photon> tracePhotons(const Scene& scene, const PhotonTracing& settings, uint64_t seed, RayCounter& counter);

}  // namespace kasha
