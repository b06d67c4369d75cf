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
#include "materials/material.h"

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

class ZhdanovBdf final : public UniformMaterial {
 public:
  // Throws std::invalid_argument with checkZhdanovParams' message.
  ZhdanovBdf(ZhdanovParams params, WavelengthRange range);

  float eval(TransportMode mode, const Vec3& wi, const Vec3& wo, float lambdaIn, float lambdaOut,
             SpectralLobe lobe) const override;
  SpectralChoice sampleSpectral(TransportMode mode, float lambdaKnown, float u) const override;
  float spectralPdf(TransportMode mode, float lambdaKnown, float lambdaOther, SpectralLobe lobe) const override;
  std::optional<DirectionSample> sampleDirection(TransportMode mode, const Vec3& wKnown, SpectralLobe lobe,
                                                 float lambdaIn, float lambdaOut, Vec2 u) const override;
  float directionPdf(TransportMode mode, const Vec3& wKnown, const Vec3& wSampled, SpectralLobe lobe, float lambdaIn,
                     float lambdaOut) const override;
  // The elastic lobe picks the gloss peak with a probability weighted by p(λ).
  BsdfFlags flags() const override {
    return flagIf(fluoresces(), BsdfFlags::Fluorescent) |
           flagIf(p_.gloss > 0.0f, BsdfFlags::WavelengthDependentDirection);
  }
  bool fluoresces() const { return excitation_.integral() > 0.0f; }
  float fluorescenceProbability(TransportMode mode, float lambdaKnown) const override {
    return probFluorescence(mode, lambdaKnown);
  }
  // absorbed = A(λ_i); reemitted = E(λ_o)·∫A (eq. 3 integrated over λ_i under unit light).
  std::optional<FluorophoreSpectra> fluorophore() const override;
  std::string describe() const override { return "zhdanov"; }

  float passive(float l) const { return p_.passive(l); }
  float A(float l) const { return p_.excitation(l); }
  float E(float l) const { return emission_.pdf(l); }
  float gloss() const { return p_.gloss; }
  float glossExponent() const { return p_.glossExponent; }
  // Probability of the fluorescent lobe given the known wavelength (light paths: λ_i; camera: λ_o).
  float probFluorescence(TransportMode mode, float lambdaKnown) const;

 private:
  float elasticWeight(float l) const { return p_.gloss + p_.passive(l); }
  float fluorescentWeight(TransportMode mode, float lambdaKnown) const;

  ZhdanovParams p_;
  SpectralDistribution excitation_;  // λ_i ∝ A on camera paths
  SpectralDistribution emission_;    // λ_o ∝ E on light paths; its pdf is the normalised E
};

}  // namespace kasha
