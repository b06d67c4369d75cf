#pragma once
// Reading kasha's own OpenEXR output back (its XYZ layer), for comparisons against a reference.
#include <string>
#include <vector>

#include "core/math.h"

namespace kasha {

struct XyzImage {
  int width = 0, height = 0;
  std::vector<Vec3> pixels;  // row-major, y down
};

// Throws InputError naming the file if it cannot be read or has no XYZ.X/Y/Z channels.
XyzImage readExrXyz(const std::string& path);

}  // namespace kasha
