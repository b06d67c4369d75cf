#include "materials/coated_fluorescent.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "materials/diffuse_lobe.h"
#include "materials/fresnel.h"

namespace kasha {
namespace {

Ior checkedCoat(Ior ior, WavelengthRange range) {
  if (std::string m = checkIor(ior, range); !m.empty()) throw std::invalid_argument("coat_ior: " + m);
  return ior;
}

}  // namespace

CoatedFluorescent::CoatedFluorescent(JungParams base, Ior coatIor, float alphaX, float alphaY, WavelengthRange range,
                                     CoatedTextures textures)
    : TexturedMaterial(JungModel(spectra_, HitReflectance{&spectra_.params.reflectance}, base.concentration,
                                 base.energyRatio),
                       coatIor_, checkedGgx(alphaX, alphaY)),
      spectra_(std::move(base), range),
      coatIor_(checkedCoat(std::move(coatIor), range)),
      textures_(std::move(textures)) {}

float CoatedModel::coatFresnel(float c, float lambda) const {
  const float eta = (*ior_)(lambda);
  return eta == 1.0f ? 0.0f : fresnelDielectric(c, eta);  // exactly 0 when index-matched, not rounding residue
}

float CoatedModel::eval(const ScatterQuery& query, const Vec3& wi, const Vec3& wo) const {
  if (!diffuse::sameSide(wi, wo)) return 0.0f;
  const float ti = 1.0f - coatFresnel(std::abs(wi.z), query.lambdaIn);
  if (query.lobe == SpectralLobe::Fluorescent) {
    const float to = 1.0f - coatFresnel(std::abs(wo.z), query.lambdaOut);
    const float ca = base_.c() * base_.a(query.lambdaIn);
    return ti * to / sqr((*ior_)(query.lambdaOut)) * ca * base_.q() * base_.e(query.lambdaOut) *
           kInvPi;  // Jung18 eq. 2, coated
  }
  const float to = 1.0f - coatFresnel(std::abs(wo.z), query.lambdaIn);
  const float base = ti * to / sqr((*ior_)(query.lambdaIn)) * (1.0f - base_.c() * base_.a(query.lambdaIn)) *
                     base_.r(query.lambdaIn) * kInvPi;  // Jung18 eq. 3, coated
  const float r = ggx_.reflection(wi, wo);
  if (r <= 0.0f) return base;
  const Vec3 h = reflectionHalfVector(wi, wo);
  return base + coatFresnel(std::abs(glm::dot(wi, h)), query.lambdaIn) * r;  // Walter07 eq. 20
}

float CoatedModel::fluorescentShare(TransportMode mode, float l) const {
  // Jung18 eqs. 6 (Importance, λ_i known) and 7 (Radiance, λ_o known), the coat's R0 added to the
  // elastic weight.
  const float ca = base_.c() * base_.a(l);
  const float fl = mode == TransportMode::Radiance ? base_.c() * base_.absorptionIntegral() * base_.q() * base_.e(l)
                                                   : ca * base_.q();
  const float el = (1.0f - ca) * base_.r(l) + coatFresnel(1.0f, l);
  return fl + el > 0.0f ? fl / (fl + el) : -1.0f;  // −1: nothing is scattered
}

float CoatedModel::probCoat(const Vec3& wKnown, float lambda) const {
  const float F = coatFresnel(std::abs(wKnown.z), lambda);
  const float base = (1.0f - F) * (1.0f - base_.c() * base_.a(lambda)) * base_.r(lambda);
  return F + base > 0.0f ? F / (F + base) : 0.0f;  // neither reflects: the base's cosine sampling
}

std::optional<DirectionSample> CoatedModel::sampleDirection(const ScatterQuery& query, const Vec3& wKnown,
                                                            Vec2 u) const {
  if (wKnown.z == 0.0f) return std::nullopt;
  if (query.lobe == SpectralLobe::Fluorescent) return diffuse::sample(wKnown, u);
  const float pc = probCoat(wKnown, query.lambdaIn);
  Vec3 w;
  if (u.x < pc) {
    w = reflectAbout(wKnown, ggx_.sampleVisible(wKnown, Vec2(std::min(u.x / pc, 0x1.fffffep-1f), u.y)));
  } else {
    const std::optional<DirectionSample> d = diffuse::sample(wKnown, Vec2((u.x - pc) / (1.0f - pc), u.y));
    if (!d) return std::nullopt;
    w = d->w;
  }
  const float pdf = directionPdf(query, wKnown, w);
  if (!(pdf > 0.0f)) return std::nullopt;  // the coat mirrored the direction below the surface
  return DirectionSample{w, pdf, false};
}

float CoatedModel::directionPdf(const ScatterQuery& query, const Vec3& wKnown, const Vec3& wSampled) const {
  const float diffusePdf = diffuse::pdf(wKnown, wSampled);
  if (query.lobe == SpectralLobe::Fluorescent) return diffusePdf;
  const float pc = probCoat(wKnown, query.lambdaIn);
  return pc * ggx_.reflectionPdf(wKnown, wSampled) + (1.0f - pc) * diffusePdf;
}

}  // namespace kasha
