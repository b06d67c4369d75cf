#pragma once
// Light selection for next-event estimation and light subpath starts (scene layer: it needs the
// scene's lights and the wavelength densities of the strategies).
#include <memory>
#include <utility>
#include <vector>

#include "core/light.h"
#include "core/spectrum.h"
#include "core/wavelength_density.h"

namespace kasha {

// Chooses lights in proportion to their power at the path's wavelength (next-event estimation:
// at a UV wavelength only UV sources are picked), and starts light subpaths with the joint
// density p(light, λ) = p(λ)·Φ_light(λ) / Σ_l Φ_l(λ): λ from the light-start wavelength strategy
// (by default the scene's total emitted power spectrum, so p(light, λ) = Φ_light(λ) / Σ_l ∫Φ_l)
// and then the light in proportion to its power at λ.
class LightSelector {
 public:
  explicit LightSelector(const std::vector<std::unique_ptr<Light>>& lights);
  // Returns the index of the chosen light and its probability, or probability 0.
  std::pair<size_t, float> select(float lambda, float u) const;
  float probability(size_t light, float lambda) const;
  // Σ_l Φ_l(λ): probability(l, λ) is lights[l]->power(λ) over it (0 where it is 0).
  float totalPower(float lambda) const { return totalPower_(lambda); }

  struct LightWavelength {
    size_t light = 0;
    float lambda = 0.0f;
    float pdf = 0.0f;  // joint: P(light | λ)·p(λ), per nm
  };
  LightWavelength sampleLightAndWavelength(const WavelengthDensity& wavelengths, float uLambda, float uLight) const;

 private:
  const std::vector<std::unique_ptr<Light>>& lights_;
  Spectrum totalPower_;  // Σ_l Φ_l(λ), summed once at load
};

}  // namespace kasha
