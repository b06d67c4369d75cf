#include "integrators/direct_emission.h"

#include "core/color.h"

namespace kasha {

std::vector<Vec3> directEmissionXyz(const Scene& scene) {
  std::vector<Vec3> xyz(scene.lights.size(), Vec3(0.0f));
  for (size_t i = 0; i < scene.shapes.size(); ++i)
    if (scene.shapeLight[i] >= 0)
      if (const std::optional<AreaEmission>& e = scene.shapes[i].emission)
        xyz[size_t(scene.shapeLight[i])] = Observer::cie1931().xyz(e->radiance, scene.range) * e->scale;
  return xyz;
}

}  // namespace kasha
