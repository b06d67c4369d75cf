#include "core/grid_density.h"

#include <algorithm>

namespace kasha {

GridDensity::GridDensity(VolumeGrid grid, const glm::mat4& toWorld, bool useGridBox)
    : grid_(std::move(grid)), toUnit_(grid_.worldToUnit(toWorld, useGridBox)) {}

Vec3 GridDensity::toUnit(const Vec3& p) const { return Vec3(toUnit_ * glm::vec4(p, 1.0f)); }

float GridDensity::density(const Vec3& p) const {
  const Vec3 u = toUnit(p);
  if (!(u.x >= 0.0f && u.y >= 0.0f && u.z >= 0.0f && u.x <= 1.0f && u.y <= 1.0f && u.z <= 1.0f)) return 0.0f;
  return grid_.lookup(u);
}

float GridDensity::extent(const Vec3& o, const Vec3& d) const {
  // The ray in the unit cube's coordinates (an affine map keeps the ray's parameter t).
  const Vec3 uo = toUnit(o), ud = Vec3(toUnit_ * glm::vec4(d, 0.0f));
  float tNear = 0.0f, tFar = kInf;
  for (int a = 0; a < 3; ++a) {
    if (ud[a] == 0.0f) {
      if (uo[a] < 0.0f || uo[a] > 1.0f) return 0.0f;
      continue;
    }
    float t0 = (0.0f - uo[a]) / ud[a], t1 = (1.0f - uo[a]) / ud[a];
    if (t0 > t1) std::swap(t0, t1);
    tNear = std::max(tNear, t0);
    tFar = std::min(tFar, t1);
  }
  return tNear <= tFar ? tFar : 0.0f;
}

}  // namespace kasha
