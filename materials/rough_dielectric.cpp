#include "materials/rough_dielectric.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "materials/fresnel.h"

namespace kasha {
namespace {

constexpr float kMinReflectProbability = 0.1f;
constexpr float kMinIndexContrast = 1e-3f;

Ior checkedIor(Ior ior, WavelengthRange range) {
  if (std::string m = checkIor(ior, range); !m.empty()) throw std::invalid_argument("ior: " + m);
  for (float l = range.min; l <= range.max; l += 1.0f)
    if (ior(l) < 1.0f + kMinIndexContrast)
      throw std::invalid_argument("ior: index of refraction " + std::to_string(ior(l)) + " at " + std::to_string(l) +
                                  " nm is within 0.001 of 1 (a rough surface needs an index contrast)");
  return ior;
}

// The refraction half vector's validity: each direction on the side of the facet it sees.
bool facetSides(const Vec3& a, const Vec3& b, const Vec3& h) {
  return glm::dot(a, h) * a.z > 0.0f && glm::dot(b, h) * b.z > 0.0f;
}

}  // namespace

RoughDielectric::RoughDielectric(Ior ior, float alphaX, float alphaY, WavelengthRange range, AlphaTexture alphaTexture)
    : TexturedMaterial(checkedIor(std::move(ior), range), checkedGgx(alphaX, alphaY)),
      alphaTexture_(std::move(alphaTexture)) {}

float RoughDielectricModel::reflectProbability(const Vec3& w, float lambda) const {
  const float F = fresnelDielectric(std::abs(w.z), sideIndex(-w, lambda) / sideIndex(w, lambda));
  return std::clamp(F, kMinReflectProbability, 1.0f - kMinReflectProbability);
}

float RoughDielectricModel::eval(const ScatterQuery& query, const Vec3& wi, const Vec3& wo) const {
  if (query.lobe != SpectralLobe::Elastic || wi.z == 0.0f || wo.z == 0.0f) return 0.0f;
  const float etaI = sideIndex(wi, query.lambdaIn), etaO = sideIndex(wo, query.lambdaIn);
  if (wi.z * wo.z > 0.0f) {
    const Vec3 h = reflectionHalfVector(wi, wo);
    return fresnelDielectric(std::abs(glm::dot(wi, h)), sideIndex(-wi, query.lambdaIn) / etaI) *
           ggx_.reflection(wi, wo);  // Walter07 eq. 20
  }
  const Vec3 h = refractionHalfVector(wi, etaI, wo, etaO);
  if (!facetSides(wi, wo, h)) return 0.0f;
  const float ih = glm::dot(wi, h), oh = glm::dot(wo, h);
  // F is the same from both sides of the facet (fresnel.h); taken from the outside direction, so
  // that f(ω_i→ω_o) and f(ω_o→ω_i) use the same rounded value.
  const bool iOutside = wi.z > 0.0f;
  const float F = fresnelDielectric(std::abs(iOutside ? ih : oh), iOutside ? etaO / etaI : etaI / etaO);
  const float denom = sqr(etaI * ih + etaO * oh);
  // Walter07 eq. 21
  return std::abs(ih * oh) / std::abs(wi.z * wo.z) * sqr(etaO) * (1.0f - F) * ggx_.d(h) * ggx_.g1(wi) *
         ggx_.g1(wo) / denom;
}

std::optional<DirectionSample> RoughDielectricModel::sampleDirection(const ScatterQuery& query, const Vec3& wKnown,
                                                                     Vec2 u) const {
  if (query.lobe != SpectralLobe::Elastic || wKnown.z == 0.0f) return std::nullopt;
  const float pr = reflectProbability(wKnown, query.lambdaIn);
  const bool reflect = u.x < pr;
  u.x = reflect ? u.x / pr : (u.x - pr) / (1.0f - pr);
  u.x = std::min(u.x, 0x1.fffffep-1f);
  const Vec3 m = ggx_.sampleVisible(wKnown, u);
  Vec3 w;
  if (reflect) {
    w = reflectAbout(wKnown, m);
  } else if (!refractAbout(wKnown, m, sideIndex(-wKnown, query.lambdaIn) / sideIndex(wKnown, query.lambdaIn), w)) {
    return std::nullopt;  // total internal reflection at m: f = 0 for refraction
  }
  const float pdf = density(wKnown, w, query.lambdaIn);
  if (!(pdf > 0.0f) || reflect != (w.z * wKnown.z > 0.0f)) return std::nullopt;  // wrong side
  return DirectionSample{w, pdf, false};
}

float RoughDielectricModel::directionPdf(const ScatterQuery& query, const Vec3& wKnown, const Vec3& wSampled) const {
  return query.lobe == SpectralLobe::Elastic ? density(wKnown, wSampled, query.lambdaIn) : 0.0f;
}

float RoughDielectricModel::density(const Vec3& wk, const Vec3& ws, float lambda) const {
  if (wk.z == 0.0f || ws.z == 0.0f) return 0.0f;
  const float pr = reflectProbability(wk, lambda);
  if (wk.z * ws.z > 0.0f) return pr * ggx_.reflectionPdf(wk, ws);  // Walter07 eq. 14
  const float etaK = sideIndex(wk, lambda), etaS = sideIndex(ws, lambda);
  const Vec3 h = refractionHalfVector(wk, etaK, ws, etaS);
  if (!facetSides(wk, ws, h)) return 0.0f;
  const float kh = glm::dot(wk, h), sh = glm::dot(ws, h);
  // Walter07 eq. 17: |dh/dω_s| = η_s²|ω_s·h| / (η_k(ω_k·h) + η_s(ω_s·h))²
  return (1.0f - pr) * ggx_.visiblePdf(wk, h) * sqr(etaS) * std::abs(sh) / sqr(etaK * kh + etaS * sh);
}

}  // namespace kasha
