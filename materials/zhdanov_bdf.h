#pragma once
// The three-part fluorescent BDF of Zhdanov, Potemin, Zhdanov, Sokolov, Ershov & Denisov (2019),
// "Photorealistic Visualization of Fluorescence Materials with Dual Surface Scattering" (Zhdanov):
//   f(λ_i, ω_i, ω_o, λ_o) = δ(λ_i − λ_o)·[f_g(ω_i, ω_o) + p(λ_i)/π] + E(λ_o)·A(λ_i)/π      (eqs. 2–3)
// - f_g: a white, non-fluorescent near-specular gloss peak of albedo ρ_g (gloss_lobe.h, §3);
// - p(λ): the coloured passive Lambert part, as an albedo (Zhdanov's f^(p) = p/π, eq. 7);
// - E(λ_o)·A(λ_i): the factorised fluorescent part (Kasha–Vavilov rule, eq. 3), E normalised to
//   ∫E dλ = 1 over the scene's wavelength range (eq. 4) and A the fluorescent albedo, the fraction
//   of light arriving at λ_i re-emitted at any other wavelength (Zhdanov's A times π, eq. 9).
// Energy is conserved when ρ_g + p(λ) + A(λ) ≤ 1 at every λ (the gloss lobe's albedo is at most ρ_g).
//
// Sampling mirrors Jung18 §5 with the elastic weight (1 − c·a)·r replaced by ρ_g + p and the
// fluorescent one c·a·Q by A: light paths choose fluorescence with A(λ_i)/(A + ρ_g + p) and λ_o ∝ E;
// camera paths with E(λ_o)∫A / (E(λ_o)∫A + ρ_g + p(λ_o)) and λ_i ∝ A. An elastic event then picks
// the gloss lobe with probability ρ_g/(ρ_g + p(λ)), else the cosine lobe; a fluorescent event is
// cosine-distributed.
#include <string>

#include "core/spectral_distribution.h"
#include "materials/factorised_fluorescent_model.h"
#include "materials/surface_texture.h"
#include "materials/textured_material.h"

namespace kasha {

struct ZhdanovParams {
  float gloss = 0.0f;            // ρ_g, white
  float glossExponent = 100.0f;  // n of the modified Phong peak
  Spectrum passive;              // p(λ)
  Spectrum excitation;           // A(λ)
  Spectrum emission;             // E(λ), any scale: normalised internally (eq. 4)
  bool allowUnphysical = false;  // ρ_g + p + A may exceed 1 (values must still be ≥ 0)
};

// Returns "" if the parameters are valid over the range, else "field: reason".
std::string checkZhdanovParams(const ZhdanovParams& p, WavelengthRange range);

// What the BDF keeps for a whole surface: its parameters and wavelength samplers.
struct ZhdanovSpectra {
  // Throws std::invalid_argument with checkZhdanovParams' message.
  ZhdanovSpectra(ZhdanovParams params, WavelengthRange range);
  ZhdanovParams params;
  SpectralDistribution excitation;  // λ_i ∝ A on camera paths
  SpectralDistribution emission;    // λ_o ∝ E on light paths; its pdf is the normalised E
};

// The BDF at one hit: the surface's spectra with this hit's ρ_g, n, p(λ) and a factor on A(λ).
struct ZhdanovHit {
  float gloss = 0.0f, glossExponent = 0.0f;
  HitReflectance passive;
  float excitationScale = 1.0f;
};

class ZhdanovModel : public FactorisedFluorescentModel {
 public:
  // `spectra` must outlive the model (the material's).
  ZhdanovModel(const ZhdanovSpectra& spectra, ZhdanovHit hit) : s_(&spectra), h_(hit) {}

  float eval(const ScatterQuery& query, const Vec3& wi, const Vec3& wo) const override;
  std::optional<DirectionSample> sampleDirection(const ScatterQuery& query, const Vec3& wKnown, Vec2 u) const override;
  float directionPdf(const ScatterQuery& query, const Vec3& wKnown, const Vec3& wSampled) const override;
  // The elastic lobe picks the gloss peak with a probability weighted by p(λ).
  BsdfFlags flags() const override {
    return flagIf(fluoresces(), BsdfFlags::Fluorescent | BsdfFlags::FactorisedFluorescence) |
           flagIf(h_.gloss > 0.0f, BsdfFlags::WavelengthDependentDirection);
  }
  bool fluoresces() const { return excitationIntegral() > 0.0f; }
  // absorbed = A(λ_i); reemitted = E(λ_o)·∫A (eq. 3 integrated over λ_i under unit light).
  std::optional<FluorophoreSpectra> fluorophoreSpectra() const;

  float passive(float l) const { return h_.passive(l); }
  float A(float l) const { return h_.excitationScale * s_->params.excitation(l); }
  float E(float l) const { return s_->emission.pdf(l); }
  float gloss() const { return h_.gloss; }
  float glossExponent() const { return h_.glossExponent; }

 private:
  // The fluorescent weight over both weights at the known wavelength (light paths: λ_i; camera: λ_o).
  float fluorescentShare(TransportMode mode, float lambdaKnown) const override;
  const SpectralDistribution& unknownWavelengthDensity(TransportMode mode) const override {
    return mode == TransportMode::Radiance ? s_->excitation : s_->emission;
  }
  float excitationIntegral() const { return h_.excitationScale * s_->excitation.integral(); }
  float elasticWeight(float l) const { return h_.gloss + passive(l); }
  float fluorescentWeight(TransportMode mode, float lambdaKnown) const;
  const ZhdanovSpectra* s_;
  ZhdanovHit h_;
};

// Textures (materials/surface_texture.h): "gloss_texture", "gloss_exponent_texture" (factors on
// ρ_g and n), "passive_texture" (on p(λ)), "excitation_texture" (a factor on A(λ)).
struct ZhdanovTextures {
  ScalarTexture gloss, glossExponent;
  ReflectanceTexture passive;
  ScalarTexture excitation;
};

class ZhdanovBdf final : public TexturedMaterial<ZhdanovModel> {
 public:
  // Throws std::invalid_argument with checkZhdanovParams' message.
  ZhdanovBdf(ZhdanovParams params, WavelengthRange range, ZhdanovTextures textures = {});
  // The untextured surface's: textures scale A by at most 1 (same support).
  std::optional<FluorophoreSpectra> fluorophore() const override { return fluorophoreSpectra(); }
  std::string describe() const override { return "zhdanov"; }
  bool textured() const override {
    return textures_.gloss.texture || textures_.glossExponent.texture || textures_.passive.texture ||
           textures_.excitation.texture;
  }
  std::vector<const Texture*> textures() const override {
    return setTextures(textures_.gloss, textures_.glossExponent, textures_.passive, textures_.excitation);
  }

 private:
  ZhdanovModel modelAt(const TexturePoint& p) const override;
  ZhdanovSpectra spectra_;
  ZhdanovTextures textures_;
};

}  // namespace kasha
