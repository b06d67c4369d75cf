#include "materials/zhdanov_bdf.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "materials/diffuse_lobe.h"
#include "materials/gloss_lobe.h"

namespace kasha {

std::string checkZhdanovParams(const ZhdanovParams& p, WavelengthRange range) {
  if (!(p.gloss >= 0.0f && p.gloss <= 1.0f)) return "gloss: " + std::to_string(p.gloss) + " is outside [0, 1]";
  if (!(p.glossExponent >= 0.0f && p.glossExponent <= 1e6f))
    return "gloss_exponent: " + std::to_string(p.glossExponent) + " is outside [0, 1e6]";
  const auto negative = [&](const Spectrum& s) { return !(s.minValue(range.min, range.max) >= 0.0f); };
  if (negative(p.passive)) return "passive: negative or non-finite value in the wavelength range";
  if (negative(p.excitation)) return "excitation: negative or non-finite value in the wavelength range";
  if (negative(p.emission)) return "emission: negative or non-finite value in the wavelength range";
  if (p.excitation.integral(range) > 0.0f && !(p.emission.integral(range) > 0.0f))
    return "emission: integrates to zero over the wavelength range, but the excitation does not";
  if (!p.allowUnphysical) {
    // Energy conservation: ρ_g + p(λ) + A(λ) ≤ 1 (the factorised part re-emits A(λ_i) in all, eq. 4).
    const Spectrum sum = Spectrum::weightedSum({{1.0f, &p.passive}, {1.0f, &p.excitation}});
    const float hi = p.gloss + sum.maxValue(range.min, range.max);
    if (hi > 1.0f + 1e-6f)
      return "passive: gloss + passive + excitation reaches " + std::to_string(hi) +
             " in the wavelength range, above 1 (the material would create energy)";
  }
  return {};
}

ZhdanovSpectra::ZhdanovSpectra(ZhdanovParams p, WavelengthRange range)
    : params(std::move(p)), excitation(params.excitation, range), emission(params.emission, range) {
  if (std::string m = checkZhdanovParams(params, range); !m.empty()) throw std::invalid_argument(m);
}

ZhdanovBdf::ZhdanovBdf(ZhdanovParams params, WavelengthRange range, ZhdanovTextures textures)
    : TexturedMaterial(spectra_, ZhdanovHit{params.gloss, params.glossExponent, HitReflectance{&spectra_.params.passive}}),
      spectra_(std::move(params), range),
      textures_(std::move(textures)) {}

ZhdanovModel ZhdanovBdf::modelAt(const TexturePoint& at) const {
  const ZhdanovParams& p = spectra_.params;
  return ZhdanovModel(spectra_, ZhdanovHit{textures_.gloss.at(p.gloss, at), textures_.glossExponent.at(p.glossExponent, at),
                                           textures_.passive.at(p.passive, at), textures_.excitation.at(1.0f, at)});
}

float ZhdanovModel::eval(const ScatterQuery& query, const Vec3& wi, const Vec3& wo) const {
  if (!diffuse::sameSide(wi, wo)) return 0.0f;
  if (query.lobe == SpectralLobe::Elastic)  // Zhdanov eq. 2, passive part: gloss peak + Lambert
    return (h_.gloss > 0.0f ? h_.gloss * gloss::value(wi, wo, h_.glossExponent) : 0.0f) +
           passive(query.lambdaIn) * kInvPi;
  return E(query.lambdaOut) * A(query.lambdaIn) * kInvPi;  // Zhdanov eq. 3
}

float ZhdanovModel::fluorescentWeight(TransportMode mode, float lambdaKnown) const {
  // Light paths: the fluorescent albedo A(λ_i). Camera paths: ∫ A(λ_i) E(λ_o) dλ_i = E(λ_o)·∫A.
  return mode == TransportMode::Importance ? A(lambdaKnown) : E(lambdaKnown) * excitationIntegral();
}

std::optional<FluorophoreSpectra> ZhdanovModel::fluorophoreSpectra() const {
  if (!fluoresces()) return std::nullopt;
  return FluorophoreSpectra{s_->params.excitation.scaled(h_.excitationScale),
                            s_->params.emission.scaled(excitationIntegral() / s_->emission.integral())};
}

float ZhdanovModel::fluorescentShare(TransportMode mode, float lambdaKnown) const {
  const float fl = fluorescentWeight(mode, lambdaKnown), el = elasticWeight(lambdaKnown);
  return fl + el > 0.0f ? fl / (fl + el) : -1.0f;
}

namespace {
// Probability that an elastic event samples the gloss peak rather than the Lambert part.
float glossChoice(float gloss, float passive) { return gloss + passive > 0.0f ? gloss / (gloss + passive) : 0.0f; }
}  // namespace

std::optional<DirectionSample> ZhdanovModel::sampleDirection(const ScatterQuery& query, const Vec3& wKnown,
                                                             Vec2 u) const {
  if (query.lobe == SpectralLobe::Fluorescent) return diffuse::sample(wKnown, u);
  const float pg = glossChoice(h_.gloss, passive(query.lambdaIn));
  std::optional<DirectionSample> s;
  if (u.x < pg) {
    s = gloss::sample(wKnown, Vec2(std::min(u.x / pg, 0x1.fffffep-1f), u.y), h_.glossExponent);
  } else {
    s = diffuse::sample(wKnown, Vec2(std::min((u.x - pg) / (1.0f - pg), 0x1.fffffep-1f), u.y));
  }
  if (!s) return std::nullopt;
  s->pdf = directionPdf(query, wKnown, s->w);
  return s;
}

float ZhdanovModel::directionPdf(const ScatterQuery& query, const Vec3& wKnown, const Vec3& wSampled) const {
  if (query.lobe == SpectralLobe::Fluorescent) return diffuse::pdf(wKnown, wSampled);
  const float pg = glossChoice(h_.gloss, passive(query.lambdaIn));
  const float lambert = (1.0f - pg) * diffuse::pdf(wKnown, wSampled);
  return pg > 0.0f ? pg * gloss::pdf(wKnown, wSampled, h_.glossExponent) + lambert : lambert;
}

}  // namespace kasha
