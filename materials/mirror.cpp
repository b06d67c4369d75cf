#include "materials/mirror.h"

#include "materials/specular_lobe.h"

namespace kasha {
namespace {

ConductorFresnel mirrorFresnel(HitReflectance r, const ComplexIndex* index) {
  return index ? ConductorFresnel{ConductorFresnel::Law::ComplexIndex, r, index} : ConductorFresnel{ConductorFresnel::Law::Constant, r};
}

}  // namespace

Mirror::Mirror(Spectrum reflectance, ReflectanceTexture texture, std::shared_ptr<const ComplexIndex> index)
    : TexturedMaterial(mirrorFresnel(HitReflectance{&spectrum_}, index.get())),
      spectrum_(std::move(reflectance)),
      texture_(std::move(texture)),
      index_(std::move(index)) {}

MirrorModel Mirror::modelAt(const TexturePoint& p) const { return MirrorModel(mirrorFresnel(texture_.at(spectrum_, p), index_.get())); }

float MirrorModel::eval(const ScatterQuery& query, const Vec3& wi, const Vec3& wo) const {
  const bool radiance = query.mode == TransportMode::Radiance;
  const Vec3& wKnown = radiance ? wo : wi;
  const Vec3& wSampled = radiance ? wi : wo;
  if (query.lobe != SpectralLobe::Elastic || wKnown.z == 0.0f ||
      !specular::matches(wSampled, specular::reflect(wKnown)))
    return 0.0f;
  return f_(std::abs(wSampled.z), query.lambdaIn) / std::abs(wSampled.z);
}

std::optional<DirectionSample> MirrorModel::sampleDirection(const ScatterQuery& query, const Vec3& wKnown, Vec2) const {
  if (query.lobe != SpectralLobe::Elastic || wKnown.z == 0.0f) return std::nullopt;
  return DirectionSample{specular::reflect(wKnown), 1.0f, true};
}

float MirrorModel::directionPdf(const ScatterQuery& query, const Vec3& wKnown, const Vec3& wSampled) const {
  const bool hit =
      query.lobe == SpectralLobe::Elastic && wKnown.z != 0.0f && specular::matches(wSampled, specular::reflect(wKnown));
  return hit ? 1.0f : 0.0f;
}

}  // namespace kasha
