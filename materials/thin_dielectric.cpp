#include "materials/thin_dielectric.h"

#include "materials/fresnel.h"
#include "materials/specular_lobe.h"

namespace kasha {

float ThinDielectric::reflectance(float cosTheta, float lambda) const {
  const float F = fresnelDielectric(cosTheta, ior_(lambda));
  return 2.0f * F / (1.0f + F);
}

float ThinDielectric::lobeProbability(const Vec3& wKnown, const Vec3& wSampled, float lambda) const {
  if (wKnown.z == 0.0f) return 0.0f;
  const float R = reflectance(std::abs(wKnown.z), lambda);
  if (wKnown.z * wSampled.z > 0.0f) return specular::matches(wSampled, specular::reflect(wKnown)) ? R : 0.0f;
  return specular::matches(wSampled, -wKnown) ? 1.0f - R : 0.0f;
}

float ThinDielectric::eval(const ScatterQuery& query, const Vec3& wi, const Vec3& wo) const {
  if (query.lobe != SpectralLobe::Elastic) return 0.0f;
  const bool radiance = query.mode == TransportMode::Radiance;
  const Vec3& wSampled = radiance ? wi : wo;
  return lobeProbability(radiance ? wo : wi, wSampled, query.lambdaIn) / std::abs(wSampled.z);
}

std::optional<DirectionSample> ThinDielectric::sampleDirection(const ScatterQuery& query, const Vec3& wKnown,
                                                               Vec2 u) const {
  if (query.lobe != SpectralLobe::Elastic || wKnown.z == 0.0f) return std::nullopt;
  const float R = reflectance(std::abs(wKnown.z), query.lambdaIn);
  if (u.x < R) return DirectionSample{specular::reflect(wKnown), R, true};
  return DirectionSample{-wKnown, 1.0f - R, true};
}

float ThinDielectric::directionPdf(const ScatterQuery& query, const Vec3& wKnown, const Vec3& wSampled) const {
  return query.lobe == SpectralLobe::Elastic ? lobeProbability(wKnown, wSampled, query.lambdaIn) : 0.0f;
}

}  // namespace kasha
