#include "core/texture.h"

#include <ImfRgbaFile.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <functional>
#include <stdexcept>

#include "core/color.h"
#include "core/error.h"
#include "core/exr_input.h"
#include "core/input_file.h"
#include "core/memory_budget.h"
#include "core/jpeg_input.h"
#include "core/stb_image_input.h"

namespace kasha {
namespace {

std::string lowerExtension(const std::string& path) {
  const size_t dot = path.find_last_of('.');
  std::string ext = dot == std::string::npos ? "" : path.substr(dot + 1);
  for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
  return ext;
}

// The one choice of decoder: each format family has one reader.
enum class ImageFamily { OpenExr, Jpeg, Stb };
struct ImageFormat {
  const char* extension;
  ImageFamily family;
  const char* name;       // in messages: "cannot read JPEG: ..."
  const char* signature;  // the file's first bytes (stb_image would otherwise take any format it recognises)
};
constexpr ImageFormat kImageFormats[] = {
    {"exr", ImageFamily::OpenExr, "OpenEXR", ""},  // OpenEXR checks its own magic number
    {"png", ImageFamily::Stb, "PNG", "\x89PNG\r\n\x1a\n"},
    {"jpg", ImageFamily::Jpeg, "JPEG", ""},  // core/jpeg_input.h checks its own signature
    {"jpeg", ImageFamily::Jpeg, "JPEG", ""},
    {"bmp", ImageFamily::Stb, "BMP", "BM"},
    {"tga", ImageFamily::Stb, "TGA", ""},  // TGA has no signature
    {"hdr", ImageFamily::Stb, "Radiance HDR", "#?"},
};

const ImageFormat& imageFormat(const std::string& path) {
  const std::string ext = lowerExtension(path);
  for (const ImageFormat& f : kImageFormats)
    if (ext == f.extension) return f;
  throw std::runtime_error("unknown image format '." + ext + "' (expected .png, .jpg, .bmp, .tga, .hdr or .exr)");
}

int channelCount(TextureChannel c) { return c == TextureChannel::Rgb ? 3 : 1; }

// Appends the texture's channels of one RGBA pixel.
void pick(TextureChannel c, float r, float g, float b, float a, std::vector<float>& out) {
  switch (c) {
    case TextureChannel::R: out.push_back(r); return;
    case TextureChannel::G: out.push_back(g); return;
    case TextureChannel::B: out.push_back(b); return;
    case TextureChannel::A: out.push_back(a); return;
    case TextureChannel::Rgb: out.insert(out.end(), {r, g, b}); return;
    case TextureChannel::Luminance: out.push_back(luminance(Vec3(r, g, b))); return;
    case TextureChannel::Mean: break;
  }
  out.push_back((r + g + b) / 3.0f);
}

struct Decoded {
  int w, h;
  std::vector<float> texels;
};

// Called with an image's size from its header, before anything is decoded; throws to refuse it.
// decodeBytes: the decoder's own buffer while reading.
using SizeCheck = std::function<void(uint64_t width, uint64_t height, uint64_t decodeBytes)>;

// Decodes an image read through core/input_file.h (a regular file only, never blocking) from
// memory once `check` has accepted the header's size (StbImageInput, JpegInput). sRGB: integer
// codes are sRGB-encoded.
template <class Input>
Decoded decodeCodes(const Input& in, TextureChannel channel, TextureEncoding encoding, const SizeCheck& check) {
  check(in.width(), in.height(), in.decodeBytes());
  const bool srgb = encoding == TextureEncoding::Srgb && !in.linear();
  Decoded d{int(in.width()), int(in.height()), {}};
  d.texels.reserve(size_t(d.w) * size_t(d.h) * size_t(channelCount(channel)));
  in.decode([&](float r, float g, float b, float a) {
    if (srgb) pick(channel, srgbDecode(r), srgbDecode(g), srgbDecode(b), a, d.texels);
    else pick(channel, r, g, b, a, d.texels);
  });
  return d;
}

// As decodeCodes, through core/exr_input.h.
Decoded decodeExr(const std::string& path, TextureChannel channel, const SizeCheck& check) {
  ExrInput in(path, "texture");
  check(in.width(), in.height(), saturatingMul(saturatingMul(in.width(), in.height()), sizeof(Imf::Rgba)));
  try {
    const std::unique_ptr<Imf::IStream> stream = in.stream();
    Imf::RgbaInputFile file(*stream);
    const Imath::Box2i dw = file.dataWindow();
    Decoded d{int(in.width()), int(in.height()), {}};
    std::vector<Imf::Rgba> px(size_t(d.w) * size_t(d.h));
    file.setFrameBuffer(px.data() - dw.min.x - ptrdiff_t(dw.min.y) * d.w, 1, size_t(d.w));
    file.readPixels(dw.min.y, dw.max.y);
    d.texels.reserve(px.size() * size_t(channelCount(channel)));
    for (const Imf::Rgba& p : px) pick(channel, p.r, p.g, p.b, p.a, d.texels);
    return d;
  } catch (const std::exception& e) {
    throw InputError(path, "", std::string("cannot read OpenEXR: ") + e.what());
  }
}

}  // namespace

std::optional<TextureChannel> parseTextureChannel(const std::string& name) {
  if (name == "mean") return TextureChannel::Mean;
  if (name == "luminance") return TextureChannel::Luminance;
  if (name == "r") return TextureChannel::R;
  if (name == "g") return TextureChannel::G;
  if (name == "b") return TextureChannel::B;
  if (name == "a") return TextureChannel::A;
  return std::nullopt;
}

std::optional<TextureEncoding> parseTextureEncoding(const std::string& name) {
  if (name == "linear") return TextureEncoding::Linear;
  if (name == "srgb") return TextureEncoding::Srgb;
  return std::nullopt;
}

std::optional<TextureWrap> parseTextureWrap(const std::string& name) {
  if (name == "repeat") return TextureWrap::Repeat;
  if (name == "clamp") return TextureWrap::Clamp;
  if (name == "mirror") return TextureWrap::Mirror;
  return std::nullopt;
}

std::optional<TextureFilter> parseTextureFilter(const std::string& name) {
  if (name == "bilinear") return TextureFilter::Bilinear;
  if (name == "nearest") return TextureFilter::Nearest;
  return std::nullopt;
}

ImageTexture::ImageTexture(int width, int height, int channels, std::vector<float> texels, TextureWrap wrap,
                           TextureFilter filter)
    : w_(width), h_(height), channels_(channels), texels_(std::move(texels)), wrap_(wrap), filter_(filter) {
  if (w_ <= 0 || h_ <= 0 || (channels_ != 1 && channels_ != 3) ||
      texels_.size() != size_t(w_) * size_t(h_) * size_t(channels_))
    throw std::invalid_argument("texture: size does not match its texels");
}

int ImageTexture::wrapIndex(int i, int n) const {
  switch (wrap_) {
    case TextureWrap::Clamp: return std::clamp(i, 0, n - 1);
    case TextureWrap::Mirror: {
      const int m = ((i % (2 * n)) + 2 * n) % (2 * n);
      return m < n ? m : 2 * n - 1 - m;
    }
    case TextureWrap::Repeat: break;
  }
  return ((i % n) + n) % n;
}

Vec2 ImageTexture::texelCoordinates(Vec2 uv) const {
  if (!std::isfinite(uv.x) || !std::isfinite(uv.y)) uv = Vec2(0.0f);
  // Reduced to one period of the wrap first, so that huge uv do not overflow an int.
  const float period = wrap_ == TextureWrap::Mirror ? 2.0f : 1.0f;
  if (wrap_ != TextureWrap::Clamp) uv -= period * glm::floor(uv / period);
  return glm::clamp(uv, Vec2(-1.0f), Vec2(2.0f)) * Vec2(float(w_), float(h_));
}

size_t ImageTexture::texelAt(int x, int yUp) const {
  return size_t(h_ - 1 - wrapIndex(yUp, h_)) * size_t(w_) + size_t(wrapIndex(x, w_));
}

size_t ImageTexture::texelIndex(Vec2 uv) const {
  const Vec2 f = texelCoordinates(uv);
  return texelAt(int(std::floor(f.x)), int(std::floor(f.y)));
}

Vec2 ImageTexture::footprint(Vec2 uv, size_t index[4]) const {
  if (filter_ == TextureFilter::Nearest) {
    index[0] = index[1] = index[2] = index[3] = texelIndex(uv);
    return Vec2(0.0f);
  }
  // Bilinear: the four texel centres around uv.
  const Vec2 f = texelCoordinates(uv) - 0.5f;
  const int x0 = int(std::floor(f.x)), y0 = int(std::floor(f.y));
  index[0] = texelAt(x0, y0);
  index[1] = texelAt(x0 + 1, y0);
  index[2] = texelAt(x0, y0 + 1);
  index[3] = texelAt(x0 + 1, y0 + 1);
  return Vec2(f.x - float(x0), f.y - float(y0));
}

namespace {
// a + t·(b − a): exactly a where t = 0 or a = b.
template <class T>
T lerp(const T& a, const T& b, float t) {
  return a + t * (b - a);
}
}  // namespace

float ImageTexture::scalar(Vec2 uv) const {
  size_t index[4];
  const Vec2 t = footprint(uv, index);
  const auto v = [&](int k) { return texels_[index[k] * size_t(channels_)]; };
  return lerp(lerp(v(0), v(1), t.x), lerp(v(2), v(3), t.x), t.y);
}

Vec2 ImageTexture::scalarGradient(Vec2 uv) const {
  if (filter_ == TextureFilter::Nearest) return Vec2(0.0f);
  size_t index[4];
  const Vec2 t = footprint(uv, index);
  const auto v = [&](int k) { return texels_[index[k] * size_t(channels_)]; };
  // scalar = lerp(lerp(v0, v1, t.x), lerp(v2, v3, t.x), t.y) with t.x = u·w − ½ − x0, t.y = v·h − ½ − y0.
  const float dx = lerp(v(1) - v(0), v(3) - v(2), t.y), dy = lerp(v(2) - v(0), v(3) - v(1), t.x);
  return Vec2(float(w_) * dx, float(h_) * dy);
}

Vec3 ImageTexture::rgb(Vec2 uv) const {
  size_t index[4];
  const Vec2 t = footprint(uv, index);
  const auto v = [&](int k) {
    const float* p = &texels_[index[k] * size_t(channels_)];
    return Vec3(p[0], p[channels_ > 1 ? 1 : 0], p[channels_ > 2 ? 2 : 0]);
  };
  return lerp(lerp(v(0), v(1), t.x), lerp(v(2), v(3), t.x), t.y);
}

std::shared_ptr<const ImageTexture> TextureLoader::load(const std::string& path, TextureChannel channel,
                                                        TextureWrap wrap, TextureFilter filter,
                                                        TextureEncoding encoding) {
  const auto key = std::make_tuple(path, channel, wrap, filter, encoding);
  if (const auto it = loaded_.find(key); it != loaded_.end()) return it->second;
  const ImageFormat& format = imageFormat(path);
  const int nc = channelCount(channel);
  // While decoding, the decoder's buffer and the texels exist at once, besides the textures so far.
  const SizeCheck check = [&](uint64_t w, uint64_t h, uint64_t decodeBytes) {
    const uint64_t texels = saturatingMul(saturatingMul(w, h), uint64_t(nc) * sizeof(float));
    const uint64_t need = std::min(std::min(texels, UINT64_MAX - decodeBytes) + decodeBytes, UINT64_MAX - bytes_) + bytes_;
    try {
      requireMemory(need,
                    "decoding this texture (" + std::to_string(w) + "×" + std::to_string(h) +
                        " pixels) besides the scene's textures before it (" + formatBytes(bytes_) + ")",
                    limit_);
    } catch (const MemoryLimitError& e) {
      throw InputError(path, "", e.what());
    }
  };
  Decoded d = format.family == ImageFamily::OpenExr ? decodeExr(path, channel, check)
              : format.family == ImageFamily::Jpeg
                  ? decodeCodes(JpegInput(path, "texture"), channel, encoding, check)
                  : decodeCodes(StbImageInput(path, "texture", format.name, format.signature), channel, encoding, check);
  for (size_t i = 0; i < d.texels.size(); ++i)
    if (!(d.texels[i] >= 0.0f && d.texels[i] <= 1.0f)) {
      const size_t px = i / size_t(nc);
      throw std::runtime_error("value " + std::to_string(d.texels[i]) + " at pixel (" + std::to_string(px % size_t(d.w)) +
                               ", " + std::to_string(px / size_t(d.w)) + ") is outside [0, 1]");
    }
  auto t = std::make_shared<const ImageTexture>(d.w, d.h, nc, std::move(d.texels), wrap, filter);
  bytes_ += t->bytes();
  loaded_.emplace(key, t);
  return t;
}

}  // namespace kasha
