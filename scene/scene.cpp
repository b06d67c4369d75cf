#include "scene/scene.h"

namespace kasha {

Bsdf Scene::mediumBsdf(int m, const Vec3& x) const {
  const Frame frame{Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)};
  const HitContext world{Vec2(0.0f), frame, frame, {}, MeshPoint{}, Vec3(0.0f), Vec3(0.0f)};
  const Medium& medium = *media[size_t(m)];
  // A spatially varying albedo (media.md §7): the model of this collision, built in place.
  if (medium.spatiallyVaryingAlbedo()) return Bsdf::inPlace(VolumeScattering(medium, medium.albedo(x)), world);
  return Bsdf(*mediumScattering[size_t(m)], world);
}

int Scene::emittingShape(const Light& l, const EmissionSample& es) const {
  if (!(glm::dot(es.n, es.n) > 0.0f)) return -1;
  return int(&static_cast<const AreaLight&>(l).shape() - shapes.data());
}

}  // namespace kasha
