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

float ThinDielectric::eval(TransportMode mode, const Vec3& wi, const Vec3& wo, float lambdaIn, float,
                           SpectralLobe lobe) const {
  if (lobe != SpectralLobe::Elastic) return 0.0f;
  const bool radiance = mode == TransportMode::Radiance;
  const Vec3& wSampled = radiance ? wi : wo;
  return lobeProbability(radiance ? wo : wi, wSampled, lambdaIn) / std::abs(wSampled.z);
}

std::optional<DirectionSample> ThinDielectric::sampleDirection(TransportMode, const Vec3& wKnown, SpectralLobe lobe,
                                                                float lambdaIn, float, Vec2 u) const {
  if (lobe != SpectralLobe::Elastic || wKnown.z == 0.0f) return std::nullopt;
  const float R = reflectance(std::abs(wKnown.z), lambdaIn);
  if (u.x < R) return DirectionSample{specular::reflect(wKnown), R, true};
  return DirectionSample{-wKnown, 1.0f - R, true};
}

float ThinDielectric::directionPdf(TransportMode, const Vec3& wKnown, const Vec3& wSampled, SpectralLobe lobe,
                                   float lambdaIn, float) const {
  return lobe == SpectralLobe::Elastic ? lobeProbability(wKnown, wSampled, lambdaIn) : 0.0f;
}

}  // namespace kasha
