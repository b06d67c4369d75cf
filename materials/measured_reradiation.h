#pragma once
// A measured bispectral reradiation matrix as a diffuse material (core/bispectral_data.h):
//   f(λ_i, ω_i, ω_o, λ_o) = [δ(λ_i − λ_o)·d(λ_i) + F(λ_o; λ_i)] / π
// with d the diagonal (elastic reflectance, linear between the measured wavelengths) and F the
// off-diagonal reradiation density per nm: at the grid points F = value / Δ_o (Δ_o the width of
// the output band, midpoints between neighbours) and bilinear in (λ_i, λ_o) in between, zero
// outside the grid. Bilinear interpolation keeps F piecewise linear along every row and every
// column, so sampling is exact in both modes:
// - Importance (λ_i known, light paths): fluorescence with A(λ_i)/(A(λ_i) + d(λ_i)), A = ∫F dλ_o,
//   then λ_o ∝ F(·; λ_i), a mixture of the two neighbouring measured columns;
// - Radiance (λ_o known, camera paths): fluorescence with B(λ_o)/(B(λ_o) + d(λ_o)), B = ∫F dλ_i,
//   then λ_i ∝ F(λ_o; ·), a mixture of the two neighbouring measured rows.
//
// Noise (at load): negative values become 0; off-diagonal values at or below `noiseFloor`, and
// every value with λ_o < λ_i (anti-Stokes: measurement noise for the fluorophores this is meant
// for), become 0. Energy: d(λ_i) + A(λ_i) (the energy reflected at λ_i) above 1 + kEnergyTolerance
// at any measured λ_i is an error unless allowUnphysical.
#include <string>
#include <vector>

#include "core/bispectral_data.h"
#include "core/spectral_distribution.h"
#include "materials/diffuse_lobe.h"
#include "materials/surface_texture.h"
#include "materials/textured_material.h"

namespace kasha {

struct MeasuredReradiationOptions {
  float noiseFloor = 0.002f;  // in the file's units (reflectance factor per output band)
  bool allowUnphysical = false;
};
// Measured matrices are noisy: a reflected energy up to 1% above 1 is accepted as noise.
constexpr float kEnergyTolerance = 0.01f;

// The measured matrix, cleaned, as densities and wavelength samplers (what the surface shares).
class MeasuredMatrix {
 public:
  // Throws InputError naming the source file and the offending wavelength on bad data.
  MeasuredMatrix(const BispectralData& data, MeasuredReradiationOptions options, WavelengthRange range);
  float diagonal(float l) const;
  float F(float lambdaOut, float lambdaIn) const;  // reradiation density per nm
  float A(float lambdaIn) const;                   // ∫F(λ_o; λ_i) dλ_o over the range
  float B(float lambdaOut) const;                  // ∫F(λ_o; λ_i) dλ_i over the range
  bool fluoresces() const { return fluoresces_; }
  // absorbed = A(λ_i), reemitted = B(λ_o).
  FluorophoreSpectra spectra() const;
  // Samples λ_other ∝ F along the line through the known wavelength (Radiance: λ_o known, λ_i
  // sampled; Importance: the reverse); pdf per nm.
  WavelengthSample sampleLine(bool radiance, float lambdaKnown, float u) const;
  // F along that line at lambdaOther: A or B times sampleLine's density.
  float lineMass(bool radiance, float lambdaKnown, float lambdaOther) const;

 private:
  // The two lines around l and their interpolation weights (zero outside the grid).
  struct Bracket {
    size_t k0 = 0, k1 = 0;
    float w0 = 0.0f, w1 = 0.0f;
  };
  static Bracket bracket(const std::vector<float>& grid, float l);
  std::vector<float> in_, out_;
  std::vector<float> diagL_, diagV_;  // the measured diagonal d(λ)
  std::vector<float> f_;              // F at the knots, f_[o * in_.size() + i], per nm
  // The measured lines as wavelength samplers (their integrals are A and B at the knots):
  std::vector<SpectralDistribution> columns_;  // per input knot: F(·; λ_i) over λ_o
  std::vector<SpectralDistribution> rows_;     // per output knot: F(λ_o; ·) over λ_i
  bool fluoresces_ = false;
};

// The material at one hit: the matrix with factors on its diagonal and its off-diagonal part.
class MeasuredModel : public DiffuseModel<BsdfModel> {
 public:
  // `matrix` must outlive the model (the material's).
  MeasuredModel(const MeasuredMatrix& matrix, float diagonalScale, float reradiationScale)
      : m_(&matrix), diagonalScale_(diagonalScale), reradiationScale_(reradiationScale) {}

  float eval(const ScatterQuery& query, const Vec3& wi, const Vec3& wo) const override;
  SpectralChoice sampleSpectral(TransportMode mode, float lambdaKnown, float u) const override;
  float spectralPdf(TransportMode mode, float lambdaKnown, float lambdaOther, SpectralLobe lobe) const override;
  BsdfFlags flags() const override {
    return flagIf(m_->fluoresces() && reradiationScale_ > 0.0f, BsdfFlags::Fluorescent);
  }
  float fluorescenceProbability(TransportMode mode, float lambdaKnown) const override {
    return probFluorescence(mode, lambdaKnown);
  }
  float diagonal(float l) const { return diagonalScale_ * m_->diagonal(l); }
  float F(float lambdaOut, float lambdaIn) const { return reradiationScale_ * m_->F(lambdaOut, lambdaIn); }
  float A(float lambdaIn) const { return reradiationScale_ * m_->A(lambdaIn); }
  float B(float lambdaOut) const { return reradiationScale_ * m_->B(lambdaOut); }
  float probFluorescence(TransportMode mode, float lambdaKnown) const;

 private:
  float fluorescentWeight(TransportMode mode, float lambdaKnown) const;
  const MeasuredMatrix* m_;
  float diagonalScale_, reradiationScale_;
};

// Textures (materials/surface_texture.h): "reflectance_texture" (a factor on the diagonal) and
// "reradiation_texture" (a factor on the off-diagonal part F).
struct MeasuredTextures {
  ScalarTexture diagonal, reradiation;
};

class MeasuredReradiation final : public TexturedMaterial<MeasuredModel> {
 public:
  // Throws InputError naming the source file and the offending wavelength on bad data.
  MeasuredReradiation(const BispectralData& data, MeasuredReradiationOptions options, WavelengthRange range,
                      MeasuredTextures textures = {})
      : TexturedMaterial(matrix_, 1.0f, 1.0f), matrix_(data, options, range), textures_(std::move(textures)) {}
  // A(λ_i) and B(λ_o): the matrix's off-diagonal row and column integrals (textures only lower them).
  std::optional<FluorophoreSpectra> fluorophore() const override {
    if (!matrix_.fluoresces()) return std::nullopt;
    return matrix_.spectra();
  }
  std::string describe() const override { return "measured_reradiation"; }
  bool textured() const override { return textures_.diagonal.texture || textures_.reradiation.texture; }
  std::vector<const Texture*> textures() const override { return setTextures(textures_.diagonal, textures_.reradiation); }

 private:
  MeasuredModel modelAt(const TexturePoint& p) const override {
    return MeasuredModel(matrix_, textures_.diagonal.at(1.0f, p), textures_.reradiation.at(1.0f, p));
  }
  MeasuredMatrix matrix_;
  MeasuredTextures textures_;
};

}  // namespace kasha
