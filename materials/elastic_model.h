#pragma once
// The spectral stage of every model that never fluoresces (bsdf_model.h): the elastic lobe is the
// only one, so the unknown wavelength is the known one (λ_o = λ_i) and the lobe's probability is 1
// wherever anything is scattered at that wavelength, 0 elsewhere; the fluorescent lobe has
// probability 0 and density 0. A model that scatters at every wavelength keeps scatters()'s
// default; one that may reflect nothing at some λ (a zero reflectance) says where.
#include "materials/bsdf_model.h"

namespace kasha {

class ElasticModel : public BsdfModel {
 public:
  SpectralChoice sampleSpectral(TransportMode, float lambdaKnown, float) const final {
    return {SpectralLobe::Elastic, lambdaKnown, scatters(lambdaKnown) ? 1.0f : 0.0f};
  }
  float spectralPdf(TransportMode, float lambdaKnown, float, SpectralLobe lobe) const final {
    return lobe == SpectralLobe::Elastic && scatters(lambdaKnown) ? 1.0f : 0.0f;
  }
  float fluorescenceProbability(TransportMode, float) const final { return 0.0f; }

 protected:
  // Whether anything is scattered at λ.
  virtual bool scatters(float) const { return true; }
  ~ElasticModel() = default;
};

}  // namespace kasha
