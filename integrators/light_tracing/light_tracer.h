#pragma once
// Light tracing: subpaths from the lights in Importance mode, each connected to the camera at
// every non-specular vertex and splatted into the pixel it lands on. A subpath carries N wavelength
// lanes (docs/wavelength-sampling.md "Hero wavelengths"; N = 1 is classic light tracing) at the
// strata of the light-start strategy's density (by default the scene's emitted power spectrum),
// the light chosen ∝ Σ_j Φ_light(λ_j). At each vertex the lanes' spectral event picks the lobe
// (Jung18 eq. 6 with the lanes' mean P_l) and the outgoing wavelengths (elastic: each its own;
// fluorescent: N fresh lanes ∝ e serving every lane before, or with settings.fluorescentLanes =
// End one lane kept at random), which the camera connection and the continued path share; the
// sensor responds at the wavelength that arrives at it.
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
  int lanes() const override { return lanes_; }

 private:
  WavelengthStrategy wavelengths_;
  int lanes_;
  FluorescentLanes atFluorescence_;
  int maxDepth_, rrDepth_;
  bool hideEmitters_;  // RenderSettings::hideEmitters
};

}  // namespace kasha
