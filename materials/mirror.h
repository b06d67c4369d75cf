#pragma once
// Smooth mirror (a polished conductor) with spectral reflectance R(λ), or the Fresnel reflectance
// of a complex index η(λ) + i·k(λ) times R(λ) (conductor_fresnel.h): elastic, specular, both
// sides of the surface.
//
// Convention for the Dirac delta (material.h, specular_lobe.h): the only direction scattered
// into is the mirror direction ω' = (−x, −y, z) of the known one, chosen with discrete
// probability 1, and there f is the delta's coefficient R(λ)/|cos θ|, so the path weight
// f·|cos θ|/pdf is R(λ) (pbrt-v4's convention for specular BxDFs). Reflection maps solid angle
// onto itself, so the value is the same in both transport modes and reciprocal. Every other
// direction gets f = 0 and density 0. With an index, R(λ) becomes F(cos θ, λ)·R(λ).
//
// R may be textured ("reflectance_texture", materials/surface_texture.h).
#include <memory>

#include "core/spectrum.h"
#include "materials/conductor_fresnel.h"
#include "materials/elastic_model.h"
#include "materials/textured_material.h"

namespace kasha {

// The model at one hit.
class MirrorModel : public ElasticModel {
 public:
  explicit MirrorModel(ConductorFresnel f) : f_(f) {}

  float eval(const ScatterQuery& query, const Vec3& wi, const Vec3& wo) const override;
  std::optional<DirectionSample> sampleDirection(const ScatterQuery& query, const Vec3& wKnown, Vec2 u) const override;
  float directionPdf(const ScatterQuery& query, const Vec3& wKnown, const Vec3& wSampled) const override;
  BsdfFlags flags() const override { return BsdfFlags::DeltaDirection; }

 private:
  bool scatters(float lambda) const override { return f_.reflects(lambda); }
  ConductorFresnel f_;
};

class Mirror final : public TexturedMaterial<MirrorModel> {
 public:
  // R(λ) at every angle, or with an index the Fresnel reflectance of η + i·k times R(λ).
  explicit Mirror(Spectrum reflectance, ReflectanceTexture texture = {}, std::shared_ptr<const ComplexIndex> index = nullptr);
  std::optional<FluorophoreSpectra> fluorophore() const override { return std::nullopt; }
  std::string describe() const override { return "mirror"; }
  bool textured() const override { return texture_.texture != nullptr; }
  std::vector<const Texture*> textures() const override { return setTextures(texture_); }
  const Spectrum& reflectance() const { return spectrum_; }

 private:
  MirrorModel modelAt(const TexturePoint& p) const override;
  Spectrum spectrum_;
  ReflectanceTexture texture_;
  std::shared_ptr<const ComplexIndex> index_;
};

}  // namespace kasha
