#pragma once
// Bidirectional path tracing for bispectral scenes (docs/bdpt-mis.md): every (s, t) strategy,
// densities both ways, every wavelength density in the MIS weights, and the two exact wavelength
// families of transport.md §3 — light subpaths sharing the camera sample's wavelength (Shared) or
// drawing their own from the light-start strategy, by default the lights' power spectrum
// (Independent), the latter joined through a connection vertex that evaluates its fluorescent
// lobe. The sensor and light-start strategies must be densities (single or mix:), which enter
// the MIS weights.
#include "core/wavelength_strategy.h"
#include "integrators/bdpt/subpaths.h"
#include "integrators/integrator.h"

namespace kasha {

class Bdpt final : public Integrator {
 public:
  // Throws std::invalid_argument if a wavelength strategy does not apply (docs/wavelength-sampling.md).
  Bdpt(const Scene& scene, const RenderSettings& settings, bdpt::WavelengthMode mode);
  Vec3 samplePixel(const Scene& scene, Vec2 pixel, Rng& rng, SampleContext& ctx) const override;
  std::string name() const override;

 private:
  WavelengthStrategy sensor_, light_;
  bdpt::WalkSettings ws_;
};

}  // namespace kasha
