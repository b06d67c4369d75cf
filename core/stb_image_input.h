#pragma once
// stb_image input for core's image readers (Debian's libstb-dev): PNG (8 and 16 bits per
// sample), JPEG, BMP, TGA and Radiance HDR. Like core/exr_input.h, the file is read whole through
// core/input_file.h and decoded from memory, and its header (stbi_info_from_memory) is available
// before any pixel is decoded, so that the caller can check the memory limit first. The
// implementation is compiled into kasha (core/stb_image_input.cpp) with the other formats (PSD,
// GIF, PIC, PNM) left out, so that sanitizers and the fuzzer (tests/fuzz/fuzz_image.cpp) see it.
#include <cstdint>
#include <functional>
#include <string>

namespace kasha {

class StbImageInput {
 public:
  // Reads `path` (InputFile's rules; `what` names the kind of file, e.g. "texture") and its header.
  // `format` names the format in messages ("PNG" → "a.png: cannot read PNG: ..."); the file must
  // begin with `signature` (may be empty). Throws InputError naming the file.
  StbImageInput(const std::string& path, const std::string& what, const std::string& format,
                const std::string& signature);

  uint64_t width() const { return width_; }
  uint64_t height() const { return height_; }
  // Radiance HDR holds linear floats; the other formats integer codes (8 or 16 bits).
  bool linear() const { return linear_; }
  // Bytes stb_image holds while decoding: its RGBA result and a working image of the same size (a
  // PNG is inflated whole, then unfiltered; a JPEG's components are upsampled whole).
  uint64_t decodeBytes() const;

  // Decodes the pixels and calls `pixel` with each one's R, G, B, A, row by row from the top:
  // integer codes divided by their maximum (255 or 65535), HDR values as they are. Throws
  // InputError naming the file if the data is corrupt.
  using PixelVisitor = std::function<void(float r, float g, float b, float a)>;
  void decode(const PixelVisitor& pixel) const;

 private:
  std::string path_, format_, bytes_;
  uint64_t width_ = 0, height_ = 0;
  bool linear_ = false, sixteenBit_ = false;
};

}  // namespace kasha
