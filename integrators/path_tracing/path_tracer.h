#pragma once
// Spectral path tracing: camera subpaths in Radiance mode, one wavelength per path segment.
// The camera's wavelength comes from the sensor strategy (any, including multi-sample MIS: one
// path per draw). At each vertex the spectral event picks the lobe and the incident wavelength
// (Jung18 eq. 7, then λ_i from the fluorescence strategy: by default the material's a(λ));
// next-event estimation and direction sampling then share that wavelength and are combined with
// the power heuristic over directions (the choice of wavelength, common to both, cancels) — unless
// the nee strategy draws next-event estimation's own λ_i after a fluorescent event, when the
// weights compare the full densities, wavelength included.
#include "scene/wavelength_strategy.h"
#include "integrators/fluorescence_sampling.h"
#include "integrators/integrator.h"

namespace kasha {

class PathTracer final : public Integrator {
 public:
  // Throws std::invalid_argument if a wavelength strategy does not apply to the scene.
  PathTracer(const Scene& scene, const RenderSettings& settings);
  Vec3 samplePixel(const Scene& scene, Vec2 pixel, Sampler& rng, SampleContext& ctx) const override;
  std::string name() const override { return "pt"; }
  // Radiance arriving at the camera along `ray` at wavelength lambda (one sample).
  float radiance(const Scene& scene, Ray ray, float lambda, Sampler& rng, RayCounter& counter) const;

 private:
  WavelengthSources sources_;
  WavelengthStrategy sensor_;
  FluorescenceSampling fluorescence_;
  FluorescenceSampling nee_;  // λ_i of next-event estimation after a fluorescent event ("event": the event's)
  int maxDepth_, rrDepth_;
};

}  // namespace kasha
