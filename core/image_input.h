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

// A file without an XYZ layer but with emissive spectral channels S0.<λ> (Fichet et al. 2021, e.g.
// from pbrt-v4 or Mitsuba 3) is integrated to XYZ (core/spectral_exr.h). Throws InputError naming
// the file if it cannot be read or has neither.
XyzImage readExrXyz(const std::string& path);

}  // namespace kasha
