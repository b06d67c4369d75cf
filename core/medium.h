#pragma once
// A homogeneous participating medium (docs/media.md): absorption σ_a(λ) and elastic scattering
// σ_s(λ) by the medium itself, with a Henyey–Greenstein phase function, and any number of
// fluorophores, each absorbing with σ_f(λ) and re-emitting a share Y (the energy yield, as
// Jung18's Q at surfaces) of what it absorbs, isotropically, with the emission spectrum e(λ)
// whatever the excitation wavelength (Kasha's rule). Coefficients are per unit of scene length.
//   σ_t(λ) = σ_a(λ) + σ_s(λ) + Σ_k σ_f,k(λ)                                     (media.md eq. 1)
// Free flight and transmittance over a path through several media are functions of the optical
// depth τ(λ) = Σ σ_t(λ)·d over its segments (media.md eq. 2): T(λ) = exp(−τ(λ)).
// A heterogeneous medium scales all of its coefficients by a density field d(x) ≥ 0 (a grid):
// σ(x, λ) = d(x)·σ(λ), and is tracked against the majorant σ̄(λ) = max d · σ_t(λ) (media.md §4).
// A homogeneous medium without fluorophores may instead vary its single-scattering albedo α(x, λ)
// in space (an albedo field, a grid; Mitsuba 3 docs: homogeneous, whose albedo may be any volume):
// σ_t(λ) stays the same everywhere (free flights are the homogeneous ones), and at x
//   σ_s(x, λ) = α(x, λ)·σ_t(λ),   σ_a(x, λ) = (1 − α(x, λ))·σ_t(λ)            (media.md eq. 11)
// with σ_t = σ_a + σ_s of the params (the σ_s given there is replaced by the field's share).
#include <memory>
#include <string>
#include <vector>

#include "core/math.h"
#include "core/rgb_spectrum.h"
#include "core/spectral_distribution.h"
#include "core/spectrum.h"

namespace kasha {

struct Fluorophore {
  Spectrum absorption;  // σ_f(λ) per unit length
  Spectrum emission;    // e(λ), any scale: normalised over the scene's range
  float yield = 0.0f;   // Y, emitted energy per absorbed energy
};

struct MediumParams {
  Spectrum absorption = Spectrum::constant(0.0f);  // σ_a(λ)
  Spectrum scattering = Spectrum::constant(0.0f);  // σ_s(λ)
  float g = 0.0f;                                  // Henyey–Greenstein asymmetry, in (−1, 1)
  std::vector<Fluorophore> fluorophores;
};

// Checks what a medium must satisfy: finite non-negative coefficients over the range whose sum
// σ_t is finite too, g in (−1, 1), yields in [0, 1] (energy conservation, as Jung18 eq. 8),
// emission spectra that are non-negative with a positive integral over the range. Returns "" or
// "field: reason".
std::string checkMediumParams(const MediumParams& p, WavelengthRange range);

// The density of a heterogeneous medium at world points (a grid, core/volume_grid.h).
class DensityField {
 public:
  virtual ~DensityField() = default;
  virtual float density(const Vec3& p) const = 0;  // d(p) ≥ 0
  virtual float maxDensity() const = 0;             // ≥ d(p) everywhere: the majorant's density
  // The distance along the ray (o, d) beyond which d is 0 (a grid's box), infinite if it never is.
  virtual float extent(const Vec3& o, const Vec3& d) const = 0;
};

// The single-scattering albedo of a medium at world points (a grid, core/grid_albedo.h): a
// reflectance-like spectrum α(x, λ) in [0, 1].
class AlbedoField {
 public:
  virtual ~AlbedoField() = default;
  virtual RgbSigmoid albedo(const Vec3& p) const = 0;
};

class Medium {
 public:
  // Throws std::invalid_argument with checkMediumParams' message, or if an albedo field comes
  // with a density field or fluorophores. `density` null: homogeneous; `albedo` null: σ_s(λ) of
  // the params everywhere.
  Medium(std::string name, MediumParams params, WavelengthRange range,
         std::shared_ptr<const DensityField> density = nullptr, std::shared_ptr<const AlbedoField> albedo = nullptr);

  const std::string& name() const { return name_; }
  const MediumParams& params() const { return params_; }
  const WavelengthRange& range() const { return range_; }
  float sigmaA(float lambda) const { return params_.absorption(lambda); }
  float sigmaS(float lambda) const { return params_.scattering(lambda); }
  float sigmaF(size_t k, float lambda) const { return params_.fluorophores[k].absorption(lambda); }
  float sigmaT(float lambda) const;  // eq. 1
  bool fluoresces() const { return fluorescent_; }
  bool heterogeneous() const { return density_ != nullptr; }
  // d(p) (1 if homogeneous) and its maximum: the coefficients at p are d(p) times the σ(λ) above.
  float density(const Vec3& p) const { return density_ ? density_->density(p) : 1.0f; }
  float maxDensity() const { return density_ ? density_->maxDensity() : 1.0f; }
  float densityExtent(const Vec3& o, const Vec3& d) const { return density_ ? density_->extent(o, d) : kInf; }
  // Whether σ_s varies in space (eq. 7), and α(p) if it does.
  bool spatiallyVaryingAlbedo() const { return albedo_ != nullptr; }
  RgbSigmoid albedo(const Vec3& p) const { return albedo_->albedo(p); }
  // Per fluorophore k: λ ∝ σ_f,k (camera paths' excitation) and λ ∝ e_k (light paths' emission;
  // its pdf is the normalised e_k).
  const SpectralDistribution& absorptionDistribution(size_t k) const { return absorption_[k]; }
  const SpectralDistribution& emissionDistribution(size_t k) const { return emission_[k]; }
  // ∫σ_f,k over the range.
  float absorptionIntegral(size_t k) const { return absorption_[k].integral(); }

 private:
  std::string name_;
  MediumParams params_;
  WavelengthRange range_;
  std::vector<SpectralDistribution> absorption_, emission_;
  std::shared_ptr<const DensityField> density_;
  std::shared_ptr<const AlbedoField> albedo_;
  bool fluorescent_ = false;
};

}  // namespace kasha
