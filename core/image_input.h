#pragma once
// Reading images: every image file (texture, measured bispectral OpenEXR, `kasha metrics` input)
// is opened by core/input_file.h's rule and decoded from memory, and the pixels its header
// declares are checked against the memory limit before anything is decoded (a 74-byte PNG may
// declare 30000×30000 pixels). Also kasha's own OpenEXR output read back (its XYZ layer), for
// comparisons against a reference.
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

// Throws InputError naming the file if it cannot be read, has no XYZ.X/Y/Z channels, declares
// more pixels than `memoryLimit` allows, or holds a non-finite value.
XyzImage readExrXyz(const std::string& path, uint64_t memoryLimit = kDefaultMemoryLimit);

}  // namespace kasha
