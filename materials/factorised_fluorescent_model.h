#pragma once
// The spectral stage of every model whose fluorescence follows Kasha's rule, its emission spectrum
// the same whatever the excitation (the Jung BBRRDF, its coated form and Zhdanov's BDF), written
// once as elastic_model.h writes the elastic-only one. From the known
// wavelength, the fluorescent lobe has probability P_fl (Jung18 eq. 7's P_c on a camera path,
// eq. 6's P_l on a light path, each model's own weights), and its unknown wavelength is drawn from
// a density that does not depend on the known one: the excitation's (λ_i ∝ a) on a camera path, the
// emission's (λ_o ∝ e) on a light path. The elastic lobe has probability 1 − P_fl. Nothing is
// scattered where both lobes' weights are 0 at the known wavelength.
#include <algorithm>

#include "core/spectral_distribution.h"
#include "materials/bsdf_model.h"

namespace kasha {

class FactorisedFluorescentModel : public BsdfModel {
 public:
  SpectralChoice sampleSpectral(TransportMode mode, float lambdaKnown, float u) const final {
    const float pFluor = fluorescentShare(mode, lambdaKnown);
    if (pFluor < 0.0f) return {};
    if (u < pFluor) {
      const WavelengthSample ws = unknownWavelengthDensity(mode).sample(std::min(u / pFluor, kBelowOne));
      if (ws.pdf <= 0.0f) return {};
      return {SpectralLobe::Fluorescent, ws.lambda, pFluor * ws.pdf};
    }
    return {SpectralLobe::Elastic, lambdaKnown, 1.0f - pFluor};
  }
  float spectralPdf(TransportMode mode, float lambdaKnown, float lambdaOther, SpectralLobe lobe) const final {
    const float pFluor = fluorescentShare(mode, lambdaKnown);
    if (pFluor < 0.0f) return 0.0f;
    if (lobe == SpectralLobe::Elastic) return 1.0f - pFluor;
    return pFluor * unknownWavelengthDensity(mode).pdf(lambdaOther);
  }
  float fluorescenceProbability(TransportMode mode, float lambdaKnown) const final {
    return std::max(fluorescentShare(mode, lambdaKnown), 0.0f);
  }

 protected:
  // P_fl given the known wavelength (λ_o in Radiance mode, λ_i in Importance mode): the fluorescent
  // lobe's weight over both lobes' weights there; −1 where both are 0 (nothing is scattered).
  virtual float fluorescentShare(TransportMode mode, float lambdaKnown) const = 0;
  // The density of the fluorescent lobe's unknown wavelength: the excitation's (Radiance mode) or
  // the emission's (Importance mode).
  virtual const SpectralDistribution& unknownWavelengthDensity(TransportMode mode) const = 0;
  ~FactorisedFluorescentModel() = default;
};

}  // namespace kasha
