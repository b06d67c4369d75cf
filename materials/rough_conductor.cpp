#include "materials/rough_conductor.h"

#include <algorithm>
#include <cmath>

namespace kasha {

RoughConductor::RoughConductor(Spectrum f0, float alphaX, float alphaY, RoughConductorTextures textures)
    : TexturedMaterial(HitReflectance{&spectrum_}, checkedGgx(alphaX, alphaY)),
      spectrum_(std::move(f0)),
      textures_(std::move(textures)) {}

RoughConductorModel RoughConductor::modelAt(const TexturePoint& p) const {
  return RoughConductorModel(textures_.f0.at(spectrum_, p), texturedGgx(ggx(), textures_.alpha, p));
}

float RoughConductorModel::fresnel(float c, float lambda) const {
  const float F0 = f0_(lambda);
  const float k = 1.0f - std::clamp(c, 0.0f, 1.0f);
  return F0 + (1.0f - F0) * sqr(sqr(k)) * k;  // Schlick 1994 eq. 15
}

float RoughConductorModel::eval(TransportMode, const Vec3& wi, const Vec3& wo, float lambdaIn, float,
                           SpectralLobe lobe) const {
  if (lobe != SpectralLobe::Elastic) return 0.0f;
  const float r = ggx_.reflection(wi, wo);
  if (r <= 0.0f) return 0.0f;
  const Vec3 h = reflectionHalfVector(wi, wo);
  return fresnel(std::abs(glm::dot(wi, h)), lambdaIn) * r;  // Walter07 eq. 20
}

std::optional<DirectionSample> RoughConductorModel::sampleDirection(TransportMode, const Vec3& wKnown, SpectralLobe lobe,
                                                                float, float, Vec2 u) const {
  if (lobe != SpectralLobe::Elastic || wKnown.z == 0.0f) return std::nullopt;
  const Vec3 w = reflectAbout(wKnown, ggx_.sampleVisible(wKnown, u));
  const float pdf = ggx_.reflectionPdf(wKnown, w);
  if (!(pdf > 0.0f)) return std::nullopt;  // mirrored below the surface
  return DirectionSample{w, pdf, false};
}

float RoughConductorModel::directionPdf(TransportMode, const Vec3& wKnown, const Vec3& wSampled, SpectralLobe lobe, float,
                                  float) const {
  return lobe == SpectralLobe::Elastic ? ggx_.reflectionPdf(wKnown, wSampled) : 0.0f;
}

}  // namespace kasha
