#pragma once
// Scalar image textures: one channel of a PNG or OpenEXR image, looked up at a surface's texture
// coordinates (Hit::uv). They drive the spatially varying material parameters (textured_jung.h).
//
// Conventions: u runs left to right, v bottom to top, so image row 0 (the top) is v ∈ [1 − 1/h, 1).
// Lookup is nearest-texel (a box filter over the texel grid) with repetition outside [0, 1)²: the
// texel containing (u, v) mod 1. PNG values are 8-bit data (0..255 → 0..1, no sRGB decoding:
// a texture holds parameters, not colours); OpenEXR values are read as they are. Every value
// must lie in [0, 1].
#include <optional>
#include <string>
#include <vector>

#include "core/math.h"
#include "core/memory_budget.h"

namespace kasha {

enum class TextureChannel { Mean, R, G, B, A };
// "mean" (of R, G, B), "r", "g", "b", "a"; nullopt otherwise.
std::optional<TextureChannel> parseTextureChannel(const std::string& name);

class ScalarTexture {
 public:
  // Row-major texels, row 0 at the top. Requires width·height = texels.size() > 0.
  ScalarTexture(int width, int height, std::vector<float> texels);
  // Reads a .png or .exr file (by extension, any case) through core/image_input.h: a regular file,
  // its pixels checked against memoryLimit from the header before decoding. Throws
  // std::runtime_error with the reason (unreadable file, unknown format, too many pixels, a value
  // outside [0, 1] with its pixel); the caller names the scene field.
  static ScalarTexture load(const std::string& path, TextureChannel channel,
                            uint64_t memoryLimit = kDefaultMemoryLimit);

  int width() const { return w_; }
  int height() const { return h_; }
  // Index (row-major) of the texel at uv.
  size_t texelIndex(Vec2 uv) const;
  float texel(size_t index) const { return texels_[index]; }
  float lookup(Vec2 uv) const { return texels_[texelIndex(uv)]; }

 private:
  int w_, h_;
  std::vector<float> texels_;
};

}  // namespace kasha
