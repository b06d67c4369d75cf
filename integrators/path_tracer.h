#pragma once
// Spectral path tracing: camera subpaths in Radiance mode, one wavelength per path segment.
// At each vertex the material's spectral stage picks the lobe and the incident wavelength
// (Jung18 eq. 7 and λ_i ∝ a(λ) at a fluorescent vertex); next-event estimation and direction
// sampling then share that wavelength and are combined with the power heuristic over directions.
// The choice of wavelength is common to both strategies, so it cancels from the MIS weights.
#include "core/sensor_sampling.h"
#include "integrators/integrator.h"

namespace kasha {

class PathTracer final : public Integrator {
 public:
  PathTracer(const Scene& scene, SensorSampling sensor, int maxDepth, int rrDepth);
  Vec3 samplePixel(const Scene& scene, Vec2 pixel, Rng& rng, SampleContext& ctx) const override;
  std::string name() const override { return "pt"; }
  // Radiance arriving at the camera along `ray` at wavelength lambda (one sample).
  float radiance(const Scene& scene, Ray ray, float lambda, Rng& rng, RayCounter& counter) const;

 private:
  SensorWavelengths sensor_;
  int maxDepth_, rrDepth_;
};

}  // namespace kasha
