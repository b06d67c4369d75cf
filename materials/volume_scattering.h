#pragma once
// What happens at a collision inside a medium (core/medium.h), as the BsdfModel of that point, so
// that every integrator samples and evaluates a medium vertex through the interface it uses at
// surfaces (docs/media.md §2). Its "f" is the volume's scattering kernel per unit length, which
// the integrator uses without a cosine (Bsdf::cosineFactor is 1 at a medium point):
//   elastic      f = σ_s(λ)·p_HG(ω_i, ω_o)                                    (media.md eq. 3)
//   fluorescent  f = Σ_k σ_f,k(λ_i)·Y_k·ê_k(λ_o) / (4π)                       (media.md eq. 4)
// with ê_k the normalised emission. The spectral stage mirrors Jung18 eqs. 6–7 (media.md eq. 5):
// with A_el = σ_s(λ) and A_fl the fluorescent kernel integrated over the unknown wavelength
// (Radiance: Σ_k Y_k·ê_k(λ_o)·∫σ_f,k; Importance: Σ_k σ_f,k(λ_i)·Y_k), the fluorescent lobe is
// chosen with A_fl/(A_el + A_fl), a fluorophore in proportion to its share of A_fl, and the unknown
// wavelength from its σ_f,k (Radiance) or ê_k (Importance); the direction from the phase function
// (elastic) or uniformly over the sphere (fluorescent, isotropic re-emission). f/pdf of a whole
// event is therefore A_el + A_fl.
//
// In a medium with an albedo field (media.md §7) σ_s is that of one point x, α(x, λ)·σ_t(λ)
// (media.md eq. 11): the model is built for the collision (Scene::mediumBsdf, in place in the Bsdf)
// with the albedo there; otherwise one model serves the whole medium.
#include <optional>

#include "core/medium.h"
#include "materials/bsdf_model.h"

namespace kasha {

// Henyey–Greenstein phase function of the angle between the light's direction of travel before
// (−ω_i) and after (ω_o) scattering: p = (1 − g²) / (4π (1 + g² − 2g·cos θ)^{3/2}), cos θ = −ω_i·ω_o.
float henyeyGreenstein(float cosTheta, float g);
// A direction whose cosine with `axis` is distributed as henyeyGreenstein (the inverse of its CDF
// in cos θ, uniform in azimuth).
Vec3 sampleHenyeyGreenstein(const Vec3& axis, float g, Vec2 u);

class VolumeScattering final : public BsdfModel {
 public:
  // `medium` must outlive the model (the scene's). `albedoHere`: α at the collision, for a medium
  // with an albedo field (Medium::albedo); nullopt: the medium's own σ_s(λ).
  explicit VolumeScattering(const Medium& medium, std::optional<RgbSigmoid> albedoHere = std::nullopt);

  float eval(const ScatterQuery& query, const Vec3& wi, const Vec3& wo) const override;
  SpectralChoice sampleSpectral(TransportMode mode, float lambdaKnown, float u) const override;
  float spectralPdf(TransportMode mode, float lambdaKnown, float lambdaOther, SpectralLobe lobe) const override;
  float fluorescenceProbability(TransportMode mode, float lambdaKnown) const override;
  std::optional<DirectionSample> sampleDirection(const ScatterQuery& query, const Vec3& wKnown, Vec2 u) const override;
  float directionPdf(const ScatterQuery& query, const Vec3& wKnown, const Vec3& wSampled) const override;
  BsdfFlags flags() const override { return flags_; }

  // A_el + A_fl at the known wavelength: what f/pdf of a sampled event is.
  float albedoWeight(TransportMode mode, float lambdaKnown) const;
  // A_fl at the known wavelength; for Radiance, the rate per unit length at which the medium's
  // fluorescence adds light at λ_o (free flights of camera paths seek it, medium_transport.h).
  float fluorescentWeight(TransportMode mode, float lambdaKnown) const;

 private:
  // Fluorophore k's share of A_fl at the known wavelength (unnormalised).
  float fluorescentShare(TransportMode mode, size_t k, float lambdaKnown) const;
  // σ_s(λ) here: α(λ)·σ_t(λ) with an albedo, else the medium's (media.md eq. 11).
  float scattering(float lambda) const;
  size_t fluorophoreCount() const { return medium_->params().fluorophores.size(); }
  const Medium* medium_;
  std::optional<RgbSigmoid> albedoHere_;
  BsdfFlags flags_;
};

}  // namespace kasha
