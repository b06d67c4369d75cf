#pragma once
// Lambertian reflector: f = r(λ)/π, elastic only, both sides of the surface.
#include "core/spectrum.h"
#include "materials/material.h"

namespace kasha {

class Lambertian final : public UniformMaterial {
 public:
  explicit Lambertian(Spectrum reflectance) : r_(std::move(reflectance)) {}

  float eval(TransportMode mode, const Vec3& wi, const Vec3& wo, float lambdaIn, float lambdaOut,
             SpectralLobe lobe) const override;
  SpectralChoice sampleSpectral(TransportMode mode, float lambdaKnown, float u) const override;
  float spectralPdf(TransportMode mode, float lambdaKnown, float lambdaOther, SpectralLobe lobe) const override;
  std::optional<DirectionSample> sampleDirection(TransportMode mode, const Vec3& wKnown, SpectralLobe lobe,
                                                 float lambdaIn, float lambdaOut, Vec2 u) const override;
  float directionPdf(TransportMode mode, const Vec3& wKnown, const Vec3& wSampled, SpectralLobe lobe, float lambdaIn,
                     float lambdaOut) const override;
  BsdfFlags flags() const override { return BsdfFlags::None; }
  float fluorescenceProbability(TransportMode, float) const override { return 0.0f; }
  std::optional<FluorophoreSpectra> fluorophore() const override { return std::nullopt; }
  std::string describe() const override { return "lambertian"; }

  const Spectrum& reflectance() const { return r_; }

 private:
  Spectrum r_;
};

}  // namespace kasha
