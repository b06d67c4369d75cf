#pragma once
// Mitsuba's volume grid files (`.vol`; Mitsuba 3 docs: gridvolume, "Volume file format"), the
// density of a heterogeneous medium. Little-endian:
//   bytes 0–2   'V', 'O', 'L'
//   byte  3     version, 3
//   int32       encoding, 1 (float32)
//   int32 × 3   cells along x, y, z
//   int32       channels: 1, 3 or 6
//   float32 × 6 the bounding box: xmin, ymin, zmin, xmax, ymax, zmax
//   float32 × x·y·z·channels   data[((z·ny + y)·nx + x)·channels + c]
// The reader trusts nothing in the bytes: the header's counts must describe exactly the bytes that
// follow it and fit the memory limit before anything is allocated for them; every value must be
// finite and not negative (kasha reads densities and albedos); the box must have positive extent.
#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <glm/mat4x4.hpp>

#include "core/math.h"

namespace kasha {

// What a lookup beyond the grid's unit cube reads (Mitsuba 3 docs: gridvolume, wrap_mode), applied
// to the cell indices of the trilinear stencil as Dr.Jit's textures do: Clamp the edge cells,
// Repeat the grid tiled (index i reads cell i mod n), Mirror the grid reflected at each face
// (i mod 2n, and 2n − 1 − that when it is n or more).
enum class GridWrap { Clamp, Repeat, Mirror };
// "clamp", "repeat", "mirror"; nullopt for any other name.
std::optional<GridWrap> gridWrapNamed(const std::string& name);

class VolumeGrid {
 public:
  // The bytes of a whole .vol file; `path` names it in messages. Throws InputError
  // ("path: header: reason", "path: data: reason") or MemoryLimitError.
  static VolumeGrid parse(const std::string& bytes, const std::string& path, uint64_t memoryLimit);
  // Reads the file `path` (core/input_file.h's rules): the header first, the data only once the
  // header has been checked against the file's size and the memory limit.
  static VolumeGrid read(const std::string& path, uint64_t memoryLimit);

  // Cells along x, y, z, and values per cell.
  const std::array<int, 3>& resolution() const { return resolution_; }
  int channels() const { return channels_; }
  // The bounding box the file stores (Mitsuba uses it only with use_grid_bbox; by default a grid
  // spans the unit cube of its to_world).
  Vec3 boxMin() const { return boxMin_; }
  Vec3 boxMax() const { return boxMax_; }
  // The value of cell (x, y, z), channel c (indices in range).
  float cell(int x, int y, int z, int c = 0) const {
    return data_[((size_t(z) * size_t(resolution_[1]) + size_t(y)) * size_t(resolution_[0]) + size_t(x)) *
                     size_t(channels_) + size_t(c)];
  }
  // Trilinear interpolation at `u` in the grid's unit cube [0, 1]³, as Mitsuba's gridvolume with
  // filter_type trilinear: cell i's value sits at the centre (i + 1/2)/n; beyond the outermost
  // centres the stencil's cells are found by `wrap` (Clamp, Mitsuba's default: the edge cells'
  // values).
  float lookup(Vec3 u, int c = 0, GridWrap wrap = GridWrap::Clamp) const;
  // lookup() at a point of the stored bounding box (mapped linearly onto the unit cube).
  float lookupInBox(Vec3 p, int c = 0) const { return lookup((p - boxMin_) / (boxMax_ - boxMin_), c); }
  // The largest value of channel c: no interpolated value exceeds it (a majorant for tracking).
  float maximum(int c = 0) const { return maximum_[size_t(c)]; }
  // The map from world points to the unit cube lookup() reads, for a grid placed as Mitsuba's
  // gridvolume: q = toWorld⁻¹·p, then (useGridBox) the stored box mapped onto [0, 1]³.
  glm::mat4 worldToUnit(const glm::mat4& toWorld, bool useGridBox) const;

 private:
  std::array<int, 3> resolution_{};
  int channels_ = 0;
  Vec3 boxMin_{0.0f}, boxMax_{1.0f};
  std::vector<float> data_;
  std::vector<float> maximum_;
};

}  // namespace kasha
