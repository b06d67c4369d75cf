#pragma once
// Lambertian reflector: f = r(λ)/π, elastic only, both sides of the surface; r may be textured
// ("reflectance_texture", materials/surface_texture.h).
#include "core/spectrum.h"
#include "materials/diffuse_lobe.h"
#include "materials/elastic_model.h"
#include "materials/textured_material.h"

namespace kasha {

// The model at one hit.
class LambertianModel : public DiffuseModel<ElasticModel> {
 public:
  explicit LambertianModel(HitReflectance r) : r_(r) {}

  float eval(const ScatterQuery& query, const Vec3& wi, const Vec3& wo) const override;
  BsdfFlags flags() const override { return BsdfFlags::None; }

 private:
  bool scatters(float lambda) const override { return r_.reflects(lambda); }
  HitReflectance r_;
};

class Lambertian final : public ReflectanceMaterial<LambertianModel> {
 public:
  using ReflectanceMaterial::ReflectanceMaterial;
  std::string describe() const override { return "lambertian"; }
};

}  // namespace kasha
