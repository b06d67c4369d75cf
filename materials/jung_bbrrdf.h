#pragma once
// The diffuse fluorescent BBRRDF of Jung, Hanika, Marschner & Dachsbacher (2018),
// "A Simple Diffuse Fluorescent BBRRDF Model" (Jung18):
//   f(λ_i, ω_i, ω_o, λ_o) = [δ(λ_i − λ_o)(1 − c·a(λ_i))·r(λ_i) + c·a(λ_i)·Q·e(λ_o)] / π   (eq. 4)
// with absorption a, emission e normalised to ∫e dλ = 1 over the scene's wavelength range,
// non-fluorescent reflectance r, energy ratio Q and concentration c; r, c and Q may be textured
// (JungTextures), so that fluorescent ink printed on paper is a c texture.
#include <string>
#include <vector>

#include "core/spectral_distribution.h"
#include "materials/diffuse_lobe.h"
#include "materials/factorised_fluorescent_model.h"
#include "materials/surface_texture.h"
#include "materials/textured_material.h"

namespace kasha {

struct JungParams {
  Spectrum absorption;   // a(λ), peak-normalised measurements are fine
  Spectrum emission;     // e(λ), any scale: normalised internally
  Spectrum reflectance;  // r(λ)
  float concentration = 0.0f;  // c
  float energyRatio = 0.0f;    // Q
  // "allow_unphysical": c, Q, a(λ) and r(λ) may exceed 1 (the material then creates energy). Still
  // required: no negative value, and c·a(λ) ≤ 1, without which the elastic weight 1 − c·a would
  // be negative.
  bool allowUnphysical = false;
};

// Eq. 8's conditions for energy conservation: c, Q, a(λ), r(λ) in [0, 1] and e ≥ 0 with a positive
// integral over the range (relaxed by allowUnphysical). Returns an empty string if they hold, else
// "field: reason".
std::string checkJungParams(const JungParams& p, WavelengthRange range);

// Reradiation matrix on a wavelength grid (eq. 5): M = R + c·a·Q·eᵀ with R = diag((1 − c·a_i)·r_i).
// Row i is the input wavelength grid[i], column j the output wavelength grid[j]; e_j is the mass of
// e in the band of grid[j] (midpoints between neighbours), so each row sums to the energy reflected
// at grid[i] — at most 1 when eq. 8 holds.
struct ReradiationMatrix {
  std::vector<float> grid;
  std::vector<std::vector<float>> m;  // m[in][out]
};

// What the BBRRDF keeps for a whole surface: its spectra and their wavelength samplers.
struct JungSpectra {
  // Throws std::invalid_argument with checkJungParams' message if eq. 8's conditions fail.
  JungSpectra(JungParams params, WavelengthRange range);
  JungParams params;
  WavelengthRange range;
  SpectralDistribution absorption;  // samples λ_i ∝ a on camera paths
  SpectralDistribution emission;    // samples λ_o ∝ e on light paths; its pdf is the normalised e
};

// The BBRRDF at one hit: the surface's spectra with this hit's r(λ), c and Q.
class JungModel : public DiffuseModel<FactorisedFluorescentModel> {
 public:
  // `spectra` must outlive the model (the material's).
  JungModel(const JungSpectra& spectra, HitReflectance r, float c, float q) : s_(&spectra), r_(r), c_(c), q_(q) {}

  float eval(const ScatterQuery& query, const Vec3& wi, const Vec3& wo) const override;
  BsdfFlags flags() const override {
    return flagIf(fluoresces(), BsdfFlags::Fluorescent | BsdfFlags::FactorisedFluorescence);
  }
  bool fluoresces() const { return c_ > 0.0f && q_ > 0.0f; }
  // absorbed = c·a(λ); reemitted = Q·(∫c·a)·e(λ) (Jung18 eq. 2 integrated over λ_i under unit light).
  std::optional<FluorophoreSpectra> fluorophoreSpectra() const;

  // Hemispherical-spectral albedo for light arriving at λ_i: ∫∫ f cos dω_o dλ_o (eq. 8's left side).
  float albedoIn(float lambdaIn) const;
  // Energy leaving at λ_o per unit of white (constant 1) incident light: ∫∫ f cos dω_i dλ_i.
  float albedoOut(float lambdaOut) const;

  // Normalised emission e(λ) (∫e = 1 over the range) and the other parameters.
  float a(float l) const { return s_->params.absorption(l); }
  float e(float l) const { return s_->emission.pdf(l); }
  float r(float l) const { return r_(l); }
  float c() const { return c_; }
  float q() const { return q_; }
  float absorptionIntegral() const { return s_->absorption.integral(); }
  // The wavelength samplers of the spectral stage: λ_i ∝ a (camera paths), λ_o ∝ e (light paths).
  const SpectralDistribution& absorptionDistribution() const { return s_->absorption; }
  const SpectralDistribution& emissionDistribution() const { return s_->emission; }
  const WavelengthRange& range() const { return s_->range; }

  ReradiationMatrix reradiationMatrix(const std::vector<float>& grid) const;

 private:
  // P_c (Jung18 eq. 7, Radiance, λ_o known) or P_l (eq. 6, Importance, λ_i known).
  float fluorescentShare(TransportMode mode, float lambdaKnown) const override;
  const SpectralDistribution& unknownWavelengthDensity(TransportMode mode) const override {
    return mode == TransportMode::Radiance ? s_->absorption : s_->emission;
  }
  const JungSpectra* s_;
  HitReflectance r_;
  float c_, q_;
};

// Textures of r(λ), c and Q (materials/surface_texture.h): "reflectance_texture", "c_texture",
// "Q_texture"; absent: the material's value.
struct JungTextures {
  ReflectanceTexture reflectance;
  ScalarTexture c, q;
  bool any() const { return reflectance.texture || c.texture || q.texture; }
  std::vector<const Texture*> list() const { return setTextures(reflectance, c, q); }
  // The model of the surface's spectra at p.
  JungModel at(const JungSpectra& s, const TexturePoint& p) const {
    return JungModel(s, reflectance.at(s.params.reflectance, p), c.at(s.params.concentration, p),
                     q.at(s.params.energyRatio, p));
  }
};

class JungBbrrdf final : public TexturedMaterial<JungModel> {
 public:
  // Throws std::invalid_argument with checkJungParams' message if eq. 8's conditions fail.
  JungBbrrdf(JungParams params, WavelengthRange range, JungTextures textures = {});
  // The untextured surface's: textures scale c and Q by at most 1, so it bounds every hit's with
  // the same support.
  std::optional<FluorophoreSpectra> fluorophore() const override { return fluorophoreSpectra(); }
  std::string describe() const override { return textured() ? "jung_fluorescent (textured)" : "jung_fluorescent"; }
  bool textured() const override { return textures_.any(); }
  std::vector<const Texture*> textures() const override { return textures_.list(); }

 private:
  JungModel modelAt(const TexturePoint& p) const override { return textures_.at(spectra_, p); }
  JungSpectra spectra_;
  JungTextures textures_;
};

}  // namespace kasha
