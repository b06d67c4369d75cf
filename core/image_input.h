#pragma once
// Reading images: every image file (texture, measured bispectral OpenEXR, `kasha metrics` input)
// is opened by core/input_file.h's rule and decoded from memory, and the pixels its header
// declares are checked against the memory limit before anything is decoded (a 74-byte PNG may
// declare 30000×30000 pixels). Also kasha's own OpenEXR output read back (its XYZ layer), for
// comparisons against a reference.
#include <ImfForward.h>

#include <cstdint>
#include <memory>
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

// An OpenEXR file read whole into memory (input_file.h) and opened from there: header() is
// available at once, pixels are decoded only by readPixels. Throws InputError naming the file.
class ExrInput {
 public:
  explicit ExrInput(const std::string& path, const std::string& what);
  ~ExrInput();
  Imf::InputFile& file() { return *file_; }
  // Another stream over the same bytes, from their start (for OpenEXR's other readers, e.g.
  // Imf::RgbaInputFile); valid while this object lives.
  std::unique_ptr<Imf::IStream> stream() const;
  // The data window's size, computed without overflow; an empty window is an InputError.
  uint64_t width() const { return width_; }
  uint64_t height() const { return height_; }

 private:
  class MemoryStream;
  std::string bytes_;
  std::unique_ptr<MemoryStream> stream_;
  std::unique_ptr<Imf::InputFile> file_;
  uint64_t width_ = 0, height_ = 0;
};

// Throws InputError naming the file if it cannot be read, has no XYZ.X/Y/Z channels, declares
// more pixels than `memoryLimit` allows, or holds a non-finite value.
XyzImage readExrXyz(const std::string& path, uint64_t memoryLimit = kDefaultMemoryLimit);

}  // namespace kasha
