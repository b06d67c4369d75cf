#pragma once
// Light tracing: subpaths from the lights in Importance mode, each connected to the pinhole at
// every non-specular vertex and splatted into the pixel it lands on. The first wavelength comes
// from the light-start strategy (by default the scene's emitted power spectrum) and the light in
// proportion to its power there (p(light, λ) = p(λ)·Φ_light(λ)/Σ_l Φ_l(λ)); at each vertex the material's spectral stage picks the lobe and the outgoing
// wavelength (Jung18 eq. 6 and λ_o ∝ e), which the camera connection and the continued path
// share; the sensor responds at the wavelength that arrives at it.
#include "scene/wavelength_strategy.h"
#include "integrators/integrator.h"

namespace kasha {

class LightTracer final : public Integrator {
 public:
  // Throws std::invalid_argument if the light-start strategy does not apply to the scene.
  LightTracer(const Scene& scene, const RenderSettings& settings);
  // Traces one light subpath (the pixel only seeds its random stream) and returns zero: all of
  // its contributions are splats.
  Vec3 samplePixel(const Scene& scene, Vec2 pixel, Sampler& rng, SampleContext& ctx) const override;
  std::string name() const override { return "lt"; }

 private:
  WavelengthStrategy wavelengths_;
  int maxDepth_, rrDepth_;
};

}  // namespace kasha
