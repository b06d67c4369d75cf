#pragma once
// Jung18's diffuse fluorescent BBRRDF (jung_bbrrdf.h) under a clear dielectric coat, the layered
// material Jung18 §8 names as future work. docs/layered.md derives it; in short, with F(θ, λ)
// the Fresnel reflectance of the coat (fresnel.h, index η(λ) from ior.h over vacuum),
// T(θ, λ) = 1 − F(θ, λ), and the coat's surface a GGX microfacet interface (ggx.h):
//
//   f = f_coat + f_base,
//   f_coat(ω_i, ω_o, λ)      = F(|ω_i·h|, λ)·D(h)·G1(ω_i)·G1(ω_o) / (4|cos θ_i||cos θ_o|)   elastic  (Walter07 eq. 20)
//   f_base elastic           = T(θ_i, λ)·T(θ_o, λ)/η(λ)² · (1 − c·a(λ))·r(λ)/π                     (Jung18 eq. 3)
//   f_base fluorescent       = T(θ_i, λ_i)·T(θ_o, λ_o)/η(λ_o)² · c·a(λ_i)·Q·e(λ_o)/π              (Jung18 eq. 2)
//
// Light enters through the coat (losing the Fresnel-reflected part at its own wavelength λ_i),
// is reflected or re-emitted by the diffuse base, and leaves through the coat at λ_o (losing the
// part reflected back down, and spreading from the medium into vacuum: radiance ÷ η(λ_o)², Veach97
// §5.2). Light the coat reflects back down onto the base is dropped (no interreflection), so the
// material conserves energy (docs/layered.md). Where the base is diffuse, where a refracted ray
// meets it does not matter, so directions enter only through the two Fresnel factors. f is
// symmetric in directions and the same in both transport modes; with η = 1 it is the base.
//
// Sampling (exactly the densities pdf() returns):
//   spectral stage  Jung18's eqs. 6/7 with the coat's normal-incidence reflectance R0(λ) added to
//                   the elastic weight (so the coat's reflection is sampled even where the base
//                   reflects nothing); the fluorescent wavelength from a (Radiance) or e (Importance).
//   direction       fluorescent: cosine-weighted on the known side. Elastic: the coat's GGX
//                   reflection (visible normals, Heitz18) with probability
//                   P_coat = F(θ_k)/(F(θ_k) + T(θ_k)·(1 − c·a)·r), else cosine-weighted; the density
//                   is the mixture of both.
#include "materials/factorised_fluorescent_model.h"
#include "materials/ggx.h"
#include "materials/ior.h"
#include "materials/jung_bbrrdf.h"
#include "materials/surface_texture.h"
#include "materials/textured_material.h"

namespace kasha {

// The model at one hit.
class CoatedModel : public FactorisedFluorescentModel {
 public:
  // `coatIor` must outlive the model (the material's).
  CoatedModel(JungModel base, const Ior& coatIor, Ggx ggx) : base_(base), ior_(&coatIor), ggx_(ggx) {}

  float eval(const ScatterQuery& query, const Vec3& wi, const Vec3& wo) const override;
  std::optional<DirectionSample> sampleDirection(const ScatterQuery& query, const Vec3& wKnown, Vec2 u) const override;
  float directionPdf(const ScatterQuery& query, const Vec3& wKnown, const Vec3& wSampled) const override;
  // The elastic lobe picks the coat with a probability weighted by F(λ) and r(λ).
  BsdfFlags flags() const override {
    return flagIf(base_.fluoresces(), BsdfFlags::Fluorescent) | BsdfFlags::WavelengthDependentDirection;
  }
  const JungModel& base() const { return base_; }
  const Ior& coatIor() const { return *ior_; }
  const Ggx& ggx() const { return ggx_; }
  // Coat Fresnel reflectance at |cos θ| = c and λ.
  float coatFresnel(float c, float lambda) const;
  // Probability of sampling the coat's reflection in the elastic directional stage.
  float probCoat(const Vec3& wKnown, float lambda) const;

 private:
  // Jung18 eqs. 7 (Radiance) and 6 (Importance) with the coat's R0 added to the elastic weight.
  float fluorescentShare(TransportMode mode, float lambdaKnown) const override;
  const SpectralDistribution& unknownWavelengthDensity(TransportMode mode) const override {
    return mode == TransportMode::Radiance ? base_.absorptionDistribution() : base_.emissionDistribution();
  }
  JungModel base_;
  const Ior* ior_;
  Ggx ggx_;
};

// Textures (materials/surface_texture.h): the base's r, c, Q (JungTextures) and "coat_alpha_texture".
struct CoatedTextures {
  JungTextures base;
  AlphaTexture coatAlpha;
};

class CoatedFluorescent final : public TexturedMaterial<CoatedModel> {
 public:
  // Throws std::invalid_argument "field: reason" for invalid base parameters (checkJungParams),
  // coat index (checkIor) or roughness (checkedGgx).
  CoatedFluorescent(JungParams base, Ior coatIor, float alphaX, float alphaY, WavelengthRange range,
                    CoatedTextures textures = {});
  // The base's (an upper bound of what crosses the coat, with the same support).
  std::optional<FluorophoreSpectra> fluorophore() const override { return base().fluorophoreSpectra(); }
  std::string describe() const override { return "coated_fluorescent (" + coatIor().describe() + ")"; }
  bool textured() const override { return textures_.base.any() || textures_.coatAlpha.any(); }
  std::vector<const Texture*> textures() const override {
    std::vector<const Texture*> t = textures_.base.list();
    for (const Texture* a : setTextures(textures_.coatAlpha.x, textures_.coatAlpha.y)) t.push_back(a);
    return t;
  }

 private:
  CoatedModel modelAt(const TexturePoint& p) const override {
    return CoatedModel(textures_.base.at(spectra_, p), coatIor_, texturedGgx(ggx(), textures_.coatAlpha, p));
  }
  JungSpectra spectra_;
  Ior coatIor_;
  CoatedTextures textures_;
};

}  // namespace kasha
