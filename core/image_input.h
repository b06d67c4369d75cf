#pragma once
// Reading images: every image file (texture, measured bispectral OpenEXR, `kasha metrics` input)
// is opened by core/input_file.h's rule and decoded from memory, and the pixels its header
// declares are checked against the memory limit before anything is decoded (a 74-byte PNG may
// declare 30000×30000 pixels). Also kasha's own OpenEXR output read back (its XYZ layer, or its
// spectral channels), for comparisons against a reference.
#include <cstdint>
#include <string>
#include <vector>

#include "core/math.h"
#include "core/memory_budget.h"


namespace kasha {

struct XyzImage {
  int width = 0, height = 0;
  std::vector<Vec3> pixels;  // row-major, y down
};

// Throws InputError naming path if width × height pixels of bytesPerPixel exceed `limit`.
void requireImageMemory(const std::string& path, uint64_t width, uint64_t height, uint64_t bytesPerPixel,
                        uint64_t limit);

// "pixel (x, y)" for the row-major index of a pixel in an image `width` pixels wide (messages).
std::string pixelName(size_t index, int width);
// Throws InputError naming `where` and the first pixel with a non-finite X, Y or Z, e.g. "pixel
// (3, 1) is not finite": images read back (`kasha metrics`, Python's kasha.metrics) are measured
// only when every value is finite.
void requireFinitePixels(const XyzImage& image, const std::string& where, const std::string& problem = "is not finite");

class ExrInput;  // core/exr_input.h

// A file without an XYZ layer but with emissive spectral channels S0.<λ> (Fichet et al. 2021, e.g.
// from pbrt-v4 or Mitsuba 3) is integrated to XYZ (core/spectral_exr.h). Throws InputError naming
// the file if it cannot be read, has neither, declares more pixels than `memoryLimit` allows, or
// holds a non-finite value.
XyzImage readExrXyz(const std::string& path, uint64_t memoryLimit = kDefaultMemoryLimit);
// The same from a file already opened as `path`.
XyzImage readExrXyz(ExrInput& in, const std::string& path, uint64_t memoryLimit);

}  // namespace kasha
