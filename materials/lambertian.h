#pragma once
// Lambertian reflector: f = r(λ)/π, elastic only, both sides of the surface; r may be textured
// ("reflectance_texture", materials/surface_texture.h).
#include "core/spectrum.h"
#include "materials/textured_material.h"

namespace kasha {

// The model at one hit.
class LambertianModel : public BsdfModel {
 public:
  explicit LambertianModel(HitReflectance r) : r_(r) {}

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

 private:
  HitReflectance r_;
};

class Lambertian final : public ReflectanceMaterial<LambertianModel> {
 public:
  using ReflectanceMaterial::ReflectanceMaterial;
  std::string describe() const override { return "lambertian"; }
};

}  // namespace kasha
