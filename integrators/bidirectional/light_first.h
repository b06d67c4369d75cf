#pragma once
// How the merged light subpath of the unified `bdpt` starts (docs/bdpt-mis.md §11): the light first,
// with a probability of its own, Q(l) ∝ ∫Φ_l dλ, then the subpath's own wavelength from the
// light-start strategy built on that light's power spectrum alone, p_l(λ). The shared lanes, which
// ride the same subpath, then know the exact probability of its light, Q(l); the own wavelength's
// joint density is Q(l)·p_l(λ) (with the default strategy `light`, Φ_l(λ)/Σ_l'∫Φ_l', the same as
// drawing λ from the total power and the light ∝ Φ_l(λ)).
#include <vector>

#include "core/wavelength_density.h"
#include "scene/scene.h"
#include "scene/wavelength_strategy.h"

namespace kasha::bidir {

class LightFirstStart {
 public:
  // Throws WavelengthStrategyError if `lightStart` is not a density (single or mix:), as the
  // light-start site requires for bdpt.
  LightFirstStart(const Scene& scene, const WavelengthSpec& lightStart);

  struct Draw {
    size_t light = 0;
    float lambda = 0.0f;
    float lightPdf = 0.0f;       // Q(l)
    float wavelengthPdf = 0.0f;  // p_l(λ), per nm
  };
  // The light with uLight, its wavelength with uLambda; pdfs 0 if nothing can be drawn.
  Draw sample(float uLight, float uLambda) const;
  float lightProbability(size_t light) const { return pmf_[light]; }
  // p_l(λ): the light-start density of light `light`'s own wavelength.
  float wavelengthPdf(size_t light, float lambda) const;

 private:
  std::vector<float> pmf_, cdf_;
  std::vector<WavelengthDensity> perLight_;  // empty for a light that emits nothing
};

}  // namespace kasha::bidir
