#include "materials/lambertian.h"

#include "materials/diffuse_lobe.h"

namespace kasha {

float LambertianModel::eval(const ScatterQuery& query, const Vec3& wi, const Vec3& wo) const {
  if (query.lobe != SpectralLobe::Elastic || !diffuse::sameSide(wi, wo)) return 0.0f;
  return r_(query.lambdaIn) * kInvPi;
}

}  // namespace kasha
