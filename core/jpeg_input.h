#pragma once
// JPEG input through libjpeg-turbo (Debian's libjpeg62-turbo-dev): baseline and progressive,
// grayscale, YCbCr and RGB, decoded to RGB. As core/stb_image_input.h, the file is read whole
// through core/input_file.h and decoded from memory, and its header is read before any pixel, so
// that the caller can check the memory limit first. libjpeg's own working memory is capped at
// decodeBytes(), and every warning it emits (a truncated file, corrupt data it would fill in with
// grey) is an error: a hostile or damaged file is refused, never half-read.
#include <cstdint>
#include <functional>
#include <string>

namespace kasha {

class JpegInput {
 public:
  // Reads `path` (InputFile's rules; `what` names the kind of file, e.g. "texture") and its header.
  // Throws InputError naming the file.
  JpegInput(const std::string& path, const std::string& what);

  uint64_t width() const { return width_; }
  uint64_t height() const { return height_; }
  bool linear() const { return false; }  // integer codes
  // Bytes libjpeg may hold while decoding: the RGB result, and a progressive file's coefficients
  // (two bytes per sample and component).
  uint64_t decodeBytes() const;

  // Decodes the pixels and calls `pixel` with each one's R, G, B (codes / 255) and A = 1, row by
  // row from the top. Throws InputError naming the file if the data is corrupt.
  using PixelVisitor = std::function<void(float r, float g, float b, float a)>;
  void decode(const PixelVisitor& pixel) const;

 private:
  std::string path_, bytes_;
  uint64_t width_ = 0, height_ = 0, components_ = 0;
};

}  // namespace kasha
