#include "materials/rough_conductor.h"

#include <algorithm>
#include <cmath>

namespace kasha {

namespace {

ConductorFresnel conductorFresnel(HitReflectance r, const ComplexIndex* index) {
  return index ? ConductorFresnel{ConductorFresnel::Law::ComplexIndex, r, index} : ConductorFresnel{ConductorFresnel::Law::Schlick, r};
}

}  // namespace

RoughConductor::RoughConductor(Spectrum f0, float alphaX, float alphaY, RoughConductorTextures textures,
                               std::shared_ptr<const ComplexIndex> index)
    : TexturedMaterial(conductorFresnel(HitReflectance{&spectrum_}, index.get()), checkedGgx(alphaX, alphaY)),
      spectrum_(std::move(f0)),
      textures_(std::move(textures)),
      index_(std::move(index)) {}

RoughConductorModel RoughConductor::modelAt(const TexturePoint& p) const {
  return RoughConductorModel(conductorFresnel(textures_.f0.at(spectrum_, p), index_.get()),
                             texturedGgx(ggx(), textures_.alpha, p));
}

float RoughConductorModel::eval(const ScatterQuery& query, const Vec3& wi, const Vec3& wo) const {
  if (query.lobe != SpectralLobe::Elastic) return 0.0f;
  const float r = ggx_.reflection(wi, wo);
  if (r <= 0.0f) return 0.0f;
  const Vec3 h = reflectionHalfVector(wi, wo);
  return f_(std::abs(glm::dot(wi, h)), query.lambdaIn) * r;  // Walter07 eq. 20
}

std::optional<DirectionSample> RoughConductorModel::sampleDirection(const ScatterQuery& query, const Vec3& wKnown,
                                                                    Vec2 u) const {
  if (query.lobe != SpectralLobe::Elastic || wKnown.z == 0.0f) return std::nullopt;
  const Vec3 w = reflectAbout(wKnown, ggx_.sampleVisible(wKnown, u));
  const float pdf = ggx_.reflectionPdf(wKnown, w);
  if (!(pdf > 0.0f)) return std::nullopt;  // mirrored below the surface
  return DirectionSample{w, pdf, false};
}

float RoughConductorModel::directionPdf(const ScatterQuery& query, const Vec3& wKnown, const Vec3& wSampled) const {
  return query.lobe == SpectralLobe::Elastic ? ggx_.reflectionPdf(wKnown, wSampled) : 0.0f;
}

}  // namespace kasha
