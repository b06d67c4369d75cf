#include "materials/dielectric.h"

#include <stdexcept>

#include "materials/fresnel.h"
#include "materials/specular_lobe.h"

namespace kasha {

SmoothDielectric::SmoothDielectric(Ior ior, WavelengthRange range) : ior_(std::move(ior)) {
  if (std::string m = checkIor(ior_, range); !m.empty()) throw std::invalid_argument(m);
}

float Dielectric::relativeEta(const Vec3& w, float lambda) const {
  const float n = ior_(lambda);
  return w.z > 0.0f ? n : 1.0f / n;
}

Dielectric::Match Dielectric::match(const Vec3& wKnown, const Vec3& wSampled, float lambda) const {
  Match m;
  if (wKnown.z == 0.0f) return m;
  const float eta = relativeEta(wKnown, lambda);
  const float F = fresnelDielectric(std::abs(wKnown.z), eta);
  if (wKnown.z * wSampled.z > 0.0f) {
    m.reflect = specular::matches(wSampled, specular::reflect(wKnown));
    m.prob = m.reflect ? F : 0.0f;
  } else {
    const std::optional<Vec3> t = specular::refract(wKnown, eta);
    m.refract = t && specular::matches(wSampled, *t);
    m.prob = m.refract ? 1.0f - F : 0.0f;
  }
  return m;
}

float Dielectric::eval(const ScatterQuery& query, const Vec3& wi, const Vec3& wo) const {
  if (query.lobe != SpectralLobe::Elastic) return 0.0f;
  const bool radiance = query.mode == TransportMode::Radiance;
  const Vec3& wKnown = radiance ? wo : wi;
  const Vec3& wSampled = radiance ? wi : wo;
  const Match m = match(wKnown, wSampled, query.lambdaIn);
  if (!m.reflect && !m.refract) return 0.0f;
  const float f = m.prob / std::abs(wSampled.z);
  // Radiance mode, refraction: × (η_o/η_i)² = 1/η² with η = η_i/η_o the relative index from ω_o's
  // side (Veach97 §5.2). Importance mode carries power, which refraction does not rescale.
  if (m.refract && radiance) return f / sqr(relativeEta(wo, query.lambdaIn));
  return f;
}

std::optional<DirectionSample> Dielectric::sampleDirection(const ScatterQuery& query, const Vec3& wKnown,
                                                           Vec2 u) const {
  if (query.lobe != SpectralLobe::Elastic || wKnown.z == 0.0f) return std::nullopt;
  const float eta = relativeEta(wKnown, query.lambdaIn);
  const float F = fresnelDielectric(std::abs(wKnown.z), eta);
  if (u.x < F) return DirectionSample{specular::reflect(wKnown), F, true};
  const std::optional<Vec3> t = specular::refract(wKnown, eta);
  if (!t) return std::nullopt;  // unreachable: total internal reflection has F = 1
  return DirectionSample{*t, 1.0f - F, true};
}

float Dielectric::directionPdf(const ScatterQuery& query, const Vec3& wKnown, const Vec3& wSampled) const {
  return query.lobe == SpectralLobe::Elastic ? match(wKnown, wSampled, query.lambdaIn).prob : 0.0f;
}

}  // namespace kasha
