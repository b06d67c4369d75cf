#include "core/grid_albedo.h"

namespace kasha {

GridAlbedo::GridAlbedo(VolumeGrid grid, const glm::mat4& toWorld, bool useGridBox, GridWrap wrap)
    : grid_(std::move(grid)), toUnit_(grid_.worldToUnit(toWorld, useGridBox)), wrap_(wrap) {}

Vec3 GridAlbedo::colour(const Vec3& p) const {
  const Vec3 u = Vec3(toUnit_ * glm::vec4(p, 1.0f));
  if (grid_.channels() == 1) return Vec3(grid_.lookup(u, 0, wrap_));
  return {grid_.lookup(u, 0, wrap_), grid_.lookup(u, 1, wrap_), grid_.lookup(u, 2, wrap_)};
}

RgbSigmoid GridAlbedo::albedo(const Vec3& p) const { return rgbToSigmoid(colour(p)); }

}  // namespace kasha
