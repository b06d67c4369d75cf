#include "materials/lambertian.h"

#include "materials/diffuse_lobe.h"

namespace kasha {

float LambertianModel::eval(TransportMode, const Vec3& wi, const Vec3& wo, float lambdaIn, float, SpectralLobe lobe) const {
  if (lobe != SpectralLobe::Elastic || !diffuse::sameSide(wi, wo)) return 0.0f;
  return r_(lambdaIn) * kInvPi;
}

SpectralChoice LambertianModel::sampleSpectral(TransportMode, float lambdaKnown, float) const {
  // The elastic lobe is the only one: probability 1 whenever anything is reflected.
  return {SpectralLobe::Elastic, lambdaKnown, r_.reflects(lambdaKnown) ? 1.0f : 0.0f};
}

float LambertianModel::spectralPdf(TransportMode, float lambdaKnown, float, SpectralLobe lobe) const {
  return lobe == SpectralLobe::Elastic && r_.reflects(lambdaKnown) ? 1.0f : 0.0f;
}

std::optional<DirectionSample> LambertianModel::sampleDirection(TransportMode, const Vec3& wKnown, SpectralLobe, float, float,
                                                            Vec2 u) const {
  return diffuse::sample(wKnown, u);
}

float LambertianModel::directionPdf(TransportMode, const Vec3& wKnown, const Vec3& wSampled, SpectralLobe, float,
                              float) const {
  return diffuse::pdf(wKnown, wSampled);
}

}  // namespace kasha
