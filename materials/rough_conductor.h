#pragma once
// Rough conductor: GGX microfacet reflection (ggx.h) with spectral Fresnel, elastic, both sides of
// the surface (like the smooth mirror).
//
//   f(ω_i, ω_o, λ) = F(|ω_i·h|, λ)·D(h)·G1(ω_i)·G1(ω_o) / (4|cos θ_i||cos θ_o|)   Walter07 eq. 20
//
// Fresnel (conductor_fresnel.h): given a reflectance, Schlick's approximation with the spectral
// reflectance at normal incidence F0(λ), F(c) = F0 + (1 − F0)(1 − c)⁵ (Schlick 1994, "An
// inexpensive BRDF model for physically-based rendering", eq. 15): a measured F0(λ) is one
// spectrum a user can find for any metal, and F0 ≤ 1 keeps F ≤ 1. Given a complex index
// η(λ) + i·k(λ) (a named metal, core/conductor_index.h), the exact Fresnel reflectance times the
// reflectance.
//
// The value is symmetric in ω_i and ω_o and the same in both transport modes (reflection maps
// solid angle onto itself). Sampling: a visible normal from the known direction (Heitz18), the
// known direction mirrored about it; density D_known(h)/(4|ω_known·h|). The reverse density is the
// same construction from the other direction. Weight f·|cos θ_sampled|/pdf = F·G1(ω_sampled) ≤ 1;
// a mirrored direction that ends up below the surface is a failed sample (energy lost to the
// single-scattering model, as in Walter07).
//
// Textures (materials/surface_texture.h): "reflectance_texture" on F0, "alpha_texture" on both α (or one each)
// (clamped to kMinAlpha).
#include <memory>

#include "core/spectrum.h"
#include "materials/conductor_fresnel.h"
#include "materials/elastic_model.h"
#include "materials/ggx.h"
#include "materials/surface_texture.h"
#include "materials/textured_material.h"

namespace kasha {

// The model at one hit. It scatters at every wavelength (ElasticModel's default): Schlick's F is
// positive away from normal incidence even where F0 = 0 (and a zero factor only costs a sample).
class RoughConductorModel : public ElasticModel {
 public:
  RoughConductorModel(ConductorFresnel f, Ggx ggx) : f_(f), ggx_(ggx) {}

  float eval(const ScatterQuery& query, const Vec3& wi, const Vec3& wo) const override;
  std::optional<DirectionSample> sampleDirection(const ScatterQuery& query, const Vec3& wKnown, Vec2 u) const override;
  float directionPdf(const ScatterQuery& query, const Vec3& wKnown, const Vec3& wSampled) const override;
  BsdfFlags flags() const override { return BsdfFlags::None; }

  const Ggx& ggx() const { return ggx_; }

 private:
  ConductorFresnel f_;
  Ggx ggx_;
};

struct RoughConductorTextures {
  ReflectanceTexture f0;
  AlphaTexture alpha;
};

class RoughConductor final : public TexturedMaterial<RoughConductorModel> {
 public:
  // Throws std::invalid_argument for α outside [kMinAlpha, kMaxAlpha] (ggx.h).
  // f0: F0(λ) for Schlick's law, or with an index the factor on its exact Fresnel reflectance.
  RoughConductor(Spectrum f0, float alphaX, float alphaY, RoughConductorTextures textures = {},
                 std::shared_ptr<const ComplexIndex> index = nullptr);
  std::optional<FluorophoreSpectra> fluorophore() const override { return std::nullopt; }
  std::string describe() const override { return "rough_conductor"; }
  bool textured() const override { return textures_.f0.texture || textures_.alpha.any(); }
  std::vector<const Texture*> textures() const override { return setTextures(textures_.f0, textures_.alpha.x, textures_.alpha.y); }

 private:
  RoughConductorModel modelAt(const TexturePoint& p) const override;
  Spectrum spectrum_;
  RoughConductorTextures textures_;
  std::shared_ptr<const ComplexIndex> index_;
};

}  // namespace kasha
