#pragma once
// What the smooth dielectrics (dielectric.h, thin_dielectric.h) share: an index n(λ) (ior.h),
// one elastic event that scatters everything at every wavelength (lossless; ElasticModel), both
// lobes Dirac deltas in direction, and a dispersive index making the directions or the lobe
// choice depend on λ.
#include "materials/elastic_model.h"
#include "materials/ior.h"
#include "materials/material.h"

namespace kasha {

class SmoothDielectric : public UniformMaterial<ElasticModel> {
 public:
  // Throws std::invalid_argument with checkIor's message if n(λ) is not valid over the range.
  SmoothDielectric(Ior ior, WavelengthRange range);
  BsdfFlags flags() const final {
    return BsdfFlags::DeltaDirection | flagIf(ior_.dispersive(), BsdfFlags::WavelengthDependentDirection);
  }
  std::optional<FluorophoreSpectra> fluorophore() const final { return std::nullopt; }
  const Ior& ior() const { return ior_; }

 protected:
  Ior ior_;
};

}  // namespace kasha
