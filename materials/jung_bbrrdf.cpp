#include "materials/jung_bbrrdf.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "materials/diffuse_lobe.h"

namespace kasha {
namespace {

std::string checkUnitSpectrum(const Spectrum& s, WavelengthRange range, const char* field, bool allowAboveOne) {
  const float lo = s.minValue(range.min, range.max), hi = s.maxValue(range.min, range.max);
  if (!std::isfinite(lo) || !std::isfinite(hi)) return std::string(field) + ": value is not finite";
  if (lo < 0.0f) return std::string(field) + ": negative value " + std::to_string(lo) + " in the wavelength range";
  if (hi > 1.0f + 1e-6f && !allowAboveOne)
    return std::string(field) + ": value " + std::to_string(hi) + " exceeds 1 in the wavelength range";
  return {};
}

}  // namespace

std::string checkJungParams(const JungParams& p, WavelengthRange range) {
  const bool any = p.allowUnphysical;
  if (!(p.concentration >= 0.0f && (any ? std::isfinite(p.concentration) : p.concentration <= 1.0f)))
    return "c: concentration " + std::to_string(p.concentration) + (any ? " is negative" : " is outside [0, 1]");
  if (!(p.energyRatio >= 0.0f && (any ? std::isfinite(p.energyRatio) : p.energyRatio <= 1.0f)))
    return "Q: energy ratio " + std::to_string(p.energyRatio) + (any ? " is negative" : " is outside [0, 1]");
  if (std::string m = checkUnitSpectrum(p.absorption, range, "absorption", any); !m.empty()) return m;
  if (std::string m = checkUnitSpectrum(p.reflectance, range, "reflectance", any); !m.empty()) return m;
  if (const float ca = p.concentration * p.absorption.maxValue(range.min, range.max); any && ca > 1.0f + 1e-6f)
    return "c: c·a reaches " + std::to_string(ca) + ", above 1: the elastic weight 1 - c·a would be negative (not "
           "allowed even with allow_unphysical)";
  if (p.emission.minValue(range.min, range.max) < 0.0f) return "emission: negative value in the wavelength range";
  if (!(p.emission.integral(range) > 0.0f)) return "emission: integrates to zero over the wavelength range";
  return {};
}

JungSpectra::JungSpectra(JungParams p, WavelengthRange r)
    : params(std::move(p)), range(r), absorption(params.absorption, r), emission(params.emission, r) {
  if (std::string m = checkJungParams(params, range); !m.empty()) throw std::invalid_argument(m);
}

JungBbrrdf::JungBbrrdf(JungParams params, WavelengthRange range, JungTextures textures)
    : TexturedMaterial(spectra_, HitReflectance{&spectra_.params.reflectance}, params.concentration,
                       params.energyRatio),
      spectra_(std::move(params), range),
      textures_(std::move(textures)) {}

float JungModel::eval(const ScatterQuery& query, const Vec3& wi, const Vec3& wo) const {
  if (!diffuse::sameSide(wi, wo)) return 0.0f;
  const float ca = c() * a(query.lambdaIn);
  if (query.lobe == SpectralLobe::Elastic) return (1.0f - ca) * r(query.lambdaIn) * kInvPi;  // Jung18 eq. 3
  return ca * q() * e(query.lambdaOut) * kInvPi;                                             // Jung18 eq. 2
}

float JungModel::fluorescentShare(TransportMode mode, float lambdaKnown) const {
  float fl, el;
  if (mode == TransportMode::Radiance) {
    // Jung18 eq. 7: P_c = c·∫a·Q·e(λ_o) / (c·∫a·Q·e(λ_o) + (1 − c·a(λ_o))·r(λ_o))
    fl = c() * absorptionIntegral() * q() * e(lambdaKnown);
    el = (1.0f - c() * a(lambdaKnown)) * r(lambdaKnown);
  } else {
    // Jung18 eq. 6: P_l = c·a(λ_i)·Q / (c·a(λ_i)·Q + (1 − c·a(λ_i))·r(λ_i))
    const float ca = c() * a(lambdaKnown);
    fl = ca * q(), el = (1.0f - ca) * r(lambdaKnown);
  }
  return fl + el > 0.0f ? fl / (fl + el) : -1.0f;
}

std::optional<FluorophoreSpectra> JungModel::fluorophoreSpectra() const {
  if (!fluoresces()) return std::nullopt;
  return FluorophoreSpectra{s_->params.absorption.scaled(c()),
                            s_->params.emission.scaled(q() * c() * absorptionIntegral() / s_->emission.integral())};
}

float JungModel::albedoIn(float lambdaIn) const {
  const float ca = c() * a(lambdaIn);
  return (1.0f - ca) * r(lambdaIn) + ca * q();
}

float JungModel::albedoOut(float lambdaOut) const {
  return (1.0f - c() * a(lambdaOut)) * r(lambdaOut) + c() * q() * absorptionIntegral() * e(lambdaOut);
}

ReradiationMatrix JungModel::reradiationMatrix(const std::vector<float>& grid) const {
  ReradiationMatrix out;
  out.grid = grid;
  const size_t n = grid.size();
  std::vector<float> eBand(n);
  for (size_t j = 0; j < n; ++j) {
    const float lo = j == 0 ? s_->range.min : 0.5f * (grid[j - 1] + grid[j]);
    const float hi = j + 1 == n ? s_->range.max : 0.5f * (grid[j] + grid[j + 1]);
    eBand[j] = s_->params.emission.integral(std::max(lo, s_->range.min), std::min(hi, s_->range.max)) / s_->emission.integral();
  }
  out.m.assign(n, std::vector<float>(n, 0.0f));
  for (size_t i = 0; i < n; ++i) {
    const float ca = c() * a(grid[i]);
    for (size_t j = 0; j < n; ++j) out.m[i][j] = ca * q() * eBand[j];  // Jung18 eq. 5: c·a·Q·eᵀ
    out.m[i][i] += (1.0f - ca) * r(grid[i]);                              // + R
  }
  return out;
}

}  // namespace kasha
