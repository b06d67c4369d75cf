#pragma once
// The density field of a heterogeneous medium from a volume grid (core/volume_grid.h), placed in
// the scene as Mitsuba's gridvolume is: a world point p maps to q = toWorld⁻¹·p, and the grid is
// read at q in the unit cube [0, 1]³, or with useGridBox at q in the box the file declares;
// trilinearly, and 0 outside (Mitsuba's heterogeneous medium samples only its grid's box).
#include <glm/mat4x4.hpp>

#include "core/medium.h"
#include "core/volume_grid.h"

namespace kasha {

class GridDensity final : public DensityField {
 public:
  // The grid must have one channel.
  GridDensity(VolumeGrid grid, const glm::mat4& toWorld, bool useGridBox);
  float density(const Vec3& p) const override;
  float maxDensity() const override { return grid_.maximum(); }
  // Where the ray leaves the grid's box (0 if it never meets it).
  float extent(const Vec3& o, const Vec3& d) const override;

 private:
  Vec3 toUnit(const Vec3& p) const;  // world point → the grid's unit cube
  VolumeGrid grid_;
  glm::mat4 toUnit_;  // world → unit cube, as one affine map
};

}  // namespace kasha
