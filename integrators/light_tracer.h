#pragma once
// Light tracing: subpaths from the lights in Importance mode, each connected to the pinhole at
// every non-specular vertex and splatted into the pixel it lands on. The light and the first
// wavelength are drawn jointly from the scene's emitted power spectrum (p(light, λ) =
// Φ_light(λ)/ΣΦ); at each vertex the material's spectral stage picks the lobe and the outgoing
// wavelength (Jung18 eq. 6 and λ_o ∝ e), which the camera connection and the continued path
// share; the sensor responds at the wavelength that arrives at it.
#include "integrators/integrator.h"

namespace kasha {

class LightTracer final : public Integrator {
 public:
  LightTracer(int maxDepth, int rrDepth) : maxDepth_(maxDepth), rrDepth_(rrDepth) {}
  // Traces one light subpath (the pixel only seeds its random stream) and returns zero: all of
  // its contributions are splats.
  Vec3 samplePixel(const Scene& scene, Vec2 pixel, Rng& rng, SampleContext& ctx) const override;
  std::string name() const override { return "lt"; }

 private:
  int maxDepth_, rrDepth_;
};

}  // namespace kasha
