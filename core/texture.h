#pragma once
// Textures: parameters that vary over a surface (the Texture interface, read at a TexturePoint),
// and image textures, the first kind (core/checkerboard_texture.h and core/mesh_attribute_texture.h
// are the others).
//
// Image textures: one channel (a scalar parameter: c, Q, roughness, …) or three (an RGB
// reflectance, turned into a spectrum by core/rgb_spectrum.h) of an image, looked up at a
// surface's texture coordinates (Hit::uv).
//
// Conventions: u runs left to right, v bottom to top, so image row 0 (the top) is v ∈ [1 − 1/h, 1)
// and texel (x, y) has its centre at ((x + ½)/w, 1 − (y + ½)/h). Bilinear filtering blends the
// four texels whose centres surround (u, v); nearest takes the texel containing it. Outside the
// texel grid the wrap mode applies to texel indices: repeat (period w), clamp (the edge texel) or
// mirror (period 2w, reflected).
//
// Formats, chosen by the file's extension (any case) in one place (texture.cpp): OpenEXR (.exr,
// core/exr_input.h); PNG with 8 or 16 bits per sample, JPEG, BMP, TGA and Radiance HDR (.png,
// .jpg/.jpeg, .bmp, .tga, .hdr; core/stb_image_input.h). Integer codes are data (0..max → 0..1,
// a texture holds parameters and linear colours) unless the texture's encoding is sRGB, when the
// sRGB transfer function linearises R, G, B (not alpha); OpenEXR and HDR values are linear and read
// as they are. Every value must lie in [0, 1].
//
// Input: every image is opened by core/input_file.h's rule and decoded from memory, so a FIFO or
// a device is refused at once and never blocks.
// Memory: TextureLoader reads each image's header first and counts the decoded size of every
// texture of the scene against the memory limit before it decodes anything.
#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <tuple>
#include <vector>

#include "core/math.h"
#include "core/memory_budget.h"

namespace kasha {

struct Shape;  // core/shape.h

// Where a texture is read: the hit's texture coordinates (Shape::surfaceUv) and, on a mesh, the
// shape, its triangle and the barycentrics (b1, b2) of corners 1 and 2 (Hit::prim, Hit::bary),
// which mesh attributes need.
struct MeshPoint {
  const Shape* shape = nullptr;  // null where no mesh is at hand (tests of uv textures, tools)
  uint32_t prim = 0;
  Vec2 bary{0.0f};
};
struct TexturePoint {
  Vec2 uv{0.0f};
  MeshPoint mesh{};
};

// A parameter that varies over a surface, with values in [0, 1]: one channel (a scalar) or three
// (a linear sRGB colour).
class Texture {
 public:
  virtual ~Texture() = default;
  // 1 or 3.
  virtual int channels() const = 0;
  // The value of a one-channel texture at p.
  virtual float scalar(const TexturePoint& p) const = 0;
  // The colour of a three-channel texture at p.
  virtual Vec3 rgb(const TexturePoint& p) const = 0;
  // (∂/∂u, ∂/∂v) of a one-channel texture's value at p (a bump map's slope): 0 unless overridden,
  // right for textures constant in pieces of the uv plane (a checkerboard). A texture that does
  // not read texture coordinates (readsUv false) has no such gradient; bump maps refuse it.
  virtual Vec2 scalarGradient(const TexturePoint&) const { return Vec2(0.0f); }
  // Whether it reads the texture coordinates (a shape using it must have them).
  virtual bool readsUv() const { return true; }
  // The mesh attribute it reads ("vertex_color", ...; core/mesh_attribute_texture.h), or "".
  virtual std::string meshAttribute() const { return {}; }
};

// An affine map of texture coordinates, uv' = A·uv + b (Mitsuba's to_uv; the identity by default).
struct UvTransform {
  glm::mat2 linear{1.0f};  // A (column-major, glm)
  Vec2 offset{0.0f};       // b
  Vec2 operator()(Vec2 uv) const { return linear * uv + offset; }
};

// Which channels of the image a texture holds: one of them (or the mean of R, G, B, or their
// luminance Y = 0.2126 R + 0.7152 G + 0.0722 B, Rec. 709) or all of R, G, B.
enum class TextureChannel { Mean, Luminance, R, G, B, A, Rgb };
enum class TextureWrap { Repeat, Clamp, Mirror };
enum class TextureFilter { Bilinear, Nearest };
// What an integer-coded image's R, G, B codes are: data (linear) or sRGB-encoded colours (IEC
// 61966-2-1; Mitsuba's bitmap without raw = true). Float images are linear either way.
enum class TextureEncoding { Linear, Srgb };

// "mean", "luminance", "r", "g", "b", "a"; nullopt otherwise (Rgb is chosen by the field, not by name).
std::optional<TextureChannel> parseTextureChannel(const std::string& name);
// "repeat", "clamp", "mirror"; nullopt otherwise.
std::optional<TextureWrap> parseTextureWrap(const std::string& name);
// "bilinear", "nearest"; nullopt otherwise.
std::optional<TextureFilter> parseTextureFilter(const std::string& name);
// "linear", "srgb"; nullopt otherwise.
std::optional<TextureEncoding> parseTextureEncoding(const std::string& name);

class ImageTexture : public Texture {
 public:
  // Row-major texels, row 0 at the top, `channels` (1 or 3) floats per texel. Throws
  // std::invalid_argument if width·height·channels ≠ texels.size() or the size is 0.
  ImageTexture(int width, int height, int channels, std::vector<float> texels, TextureWrap wrap = TextureWrap::Repeat,
               TextureFilter filter = TextureFilter::Bilinear);

  int width() const { return w_; }
  int height() const { return h_; }
  int channels() const override { return channels_; }
  // The filtered value at uv of a one-channel texture. Non-finite uv reads (0, 0).
  float scalar(Vec2 uv) const;
  // The filtered colour at uv of a three-channel texture.
  Vec3 rgb(Vec2 uv) const;
  float scalar(const TexturePoint& p) const override { return scalar(p.uv); }
  Vec3 rgb(const TexturePoint& p) const override { return rgb(p.uv); }
  // (∂/∂u, ∂/∂v) of scalar(uv): bilinear filtering's derivative within the four texels it blends
  // (w·∂/∂x and h·∂/∂y in texel units); 0 for nearest filtering, which is piecewise constant.
  Vec2 scalarGradient(Vec2 uv) const;
  Vec2 scalarGradient(const TexturePoint& p) const override { return scalarGradient(p.uv); }
  // Row-major index of the texel containing uv (wrapped), and the first channel of texel i.
  size_t texelIndex(Vec2 uv) const;
  float texel(size_t i) const { return texels_[i * size_t(channels_)]; }
  // Bytes held by the texels.
  uint64_t bytes() const { return uint64_t(texels_.size()) * sizeof(float); }

 private:
  // The four texels that filtering blends at uv (x0y0, x1y0, x0y1, x1y1; nearest: one texel four
  // times) and the blend's fractions along x and y. Blending by nested a + t·(b − a) returns a
  // constant image's value exactly (a textured material with a constant image is the untextured one).
  Vec2 footprint(Vec2 uv, size_t index[4]) const;
  // Continuous texel coordinates of uv: u·w to the right, v·h up from the bottom row; texel
  // centres at integers + ½.
  Vec2 texelCoordinates(Vec2 uv) const;
  // Row-major index of texel (x, row yUp counted from the bottom), wrapped.
  size_t texelAt(int x, int yUp) const;
  int wrapIndex(int i, int n) const;

  int w_, h_, channels_;
  std::vector<float> texels_;
  TextureWrap wrap_;
  TextureFilter filter_;
};

// Loads textures for one scene: checks the memory limit from each image's header, decodes,
// checks the values, and shares a texture used by several fields with the same settings.
class TextureLoader {
 public:
  explicit TextureLoader(uint64_t memoryLimit) : limit_(memoryLimit) {}
  // Opens the image file (its format by extension, any case: see above) through
  // core/input_file.h (a regular file only: a FIFO or a device is refused at once) and decodes it
  // from memory. Throws
  // InputError naming the file (unreadable, not a regular file, its header's pixels with the
  // textures so far over the memory limit) or std::runtime_error with the reason (unknown
  // format, a value outside [0, 1] with its pixel); the caller names the field.
  std::shared_ptr<const ImageTexture> load(const std::string& path, TextureChannel channel, TextureWrap wrap,
                                           TextureFilter filter, TextureEncoding encoding = TextureEncoding::Linear);
  // Bytes held by the textures loaded so far.
  uint64_t bytes() const { return bytes_; }

 private:
  uint64_t limit_, bytes_ = 0;
  std::map<std::tuple<std::string, TextureChannel, TextureWrap, TextureFilter, TextureEncoding>,
           std::shared_ptr<const ImageTexture>>
      loaded_;
};

}  // namespace kasha
