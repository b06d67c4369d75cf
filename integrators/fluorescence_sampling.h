#pragma once
// The spectral event of a camera path (Radiance mode) with the excitation wavelength λ_i of the
// fluorescent lobe drawn from a wavelength strategy instead of the material's own density
// (docs/wavelength-sampling.md). The lobe is chosen as the material chooses it (Jung18 eq. 7's P_c,
// Bsdf::fluorescenceProbability), so the event's density is P_c·p(λ_i) for the fluorescent lobe
// and the material's elastic probability otherwise; with the strategy "material" the material
// samples the whole event itself.
#include <memory>
#include <vector>

#include "scene/wavelength_strategy.h"
#include "materials/material.h"

namespace kasha {

class FluorescenceSampling {
 public:
  // site: Fluorescence (the event; "material" keeps the material's sampling) or Nee (next-event
  // estimation; "event" reuses the event's wavelength). Throws WavelengthStrategyError if `spec`
  // is not a density or misses a fluorophore's absorption.
  FluorescenceSampling(const WavelengthSpec& spec, const WavelengthSources& sources, size_t materialCount,
                       WavelengthSite site = WavelengthSite::Fluorescence);
  SpectralChoice sample(const Bsdf& bsdf, size_t materialIndex, float lambdaOut, float u) const;
  // True if the strategy draws λ_i at this material (not "material" or "event", not a
  // non-fluorescent material).
  bool draws(size_t materialIndex) const { return perMaterial_[materialIndex] != nullptr; }
  // The excitation wavelength alone, once the fluorescent lobe has been chosen: λ_i and its
  // density p(λ_i). Needs a strategy other than "material".
  WavelengthSample sampleExcitation(size_t materialIndex, float u) const;
  // The density sampleExcitation draws from (needs draws(materialIndex)).
  const WavelengthDensity& density(size_t materialIndex) const { return perMaterial_[materialIndex]->density(); }
  // Density of sample() choosing (lobe, lambdaIn) given lambdaOut.
  float pdf(const Bsdf& bsdf, size_t materialIndex, float lambdaOut, float lambdaIn, SpectralLobe lobe) const;

 private:
  std::vector<std::unique_ptr<WavelengthStrategy>> perMaterial_;  // null: the material's own sampling
};

}  // namespace kasha
