#pragma once
// OpenEXR input for core's image readers (textures, measured bispectral images, renders read
// back): the file is read whole through core/input_file.h and decoded from memory, so OpenEXR
// never opens a path itself. Internal to core: its header exposes OpenEXR's types.
#include <ImfForward.h>

#include <cstdint>
#include <memory>
#include <string>

namespace kasha {

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

}  // namespace kasha
