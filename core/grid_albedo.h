#pragma once
// The albedo field of a homogeneous medium from a volume grid (core/volume_grid.h; media.md §7),
// placed as Mitsuba's gridvolume is (as core/grid_density.h places a density): a world point p is
// read at q = toWorld⁻¹·p in the grid's unit cube (or, with useGridBox, in the box the file
// declares), trilinearly, and beyond the cube as `wrap` says (Mitsuba 3 docs: gridvolume,
// wrap_mode). A 3-channel grid holds linear sRGB, a 1-channel one grey (the same value in R, G, B).
// The colour is interpolated first and then upsampled to a reflectance spectrum by the Jakob–Hanika
// sigmoid (core/rgb_spectrum.h); Mitsuba upsamples each cell and interpolates the spectra instead,
// which gives the same colour at the cells and within cells of one colour, and other metamers
// between them.
#include <glm/mat4x4.hpp>

#include "core/medium.h"
#include "core/volume_grid.h"

namespace kasha {

class GridAlbedo final : public AlbedoField {
 public:
  // The grid must have 1 or 3 channels with values in [0, 1] (the caller checks: grid.maximum()).
  GridAlbedo(VolumeGrid grid, const glm::mat4& toWorld, bool useGridBox, GridWrap wrap);
  RgbSigmoid albedo(const Vec3& p) const override;
  // The interpolated linear sRGB colour at p (what albedo() upsamples).
  Vec3 colour(const Vec3& p) const;

 private:
  VolumeGrid grid_;
  glm::mat4 toUnit_;  // world → unit cube, as one affine map
  GridWrap wrap_;
};

}  // namespace kasha
