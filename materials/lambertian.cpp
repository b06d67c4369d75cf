#include "materials/lambertian.h"

#include "materials/diffuse_lobe.h"

namespace kasha {

float LambertianModel::eval(TransportMode, const Vec3& wi, const Vec3& wo, float lambdaIn, float, SpectralLobe lobe) const {
  if (lobe != SpectralLobe::Elastic || !diffuse::sameSide(wi, wo)) return 0.0f;
  return r_(lambdaIn) * kInvPi;
}

}  // namespace kasha
