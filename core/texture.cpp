#include "core/texture.h"

#include <ImfRgbaFile.h>
#include <png.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <stdexcept>

#include "core/error.h"
#include "core/exr_input.h"
#include "core/image_input.h"
#include "core/input_file.h"

namespace kasha {
namespace {

std::string lowerExtension(const std::string& path) {
  const size_t dot = path.find_last_of('.');
  std::string ext = dot == std::string::npos ? "" : path.substr(dot + 1);
  for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
  return ext;
}

float pick(TextureChannel c, float r, float g, float b, float a) {
  switch (c) {
    case TextureChannel::R: return r;
    case TextureChannel::G: return g;
    case TextureChannel::B: return b;
    case TextureChannel::A: return a;
    case TextureChannel::Mean: break;
  }
  return (r + g + b) / 3.0f;
}

// Bytes per pixel while decoding: the RGBA buffer (8-bit for PNG, half for OpenEXR) and the texels.
constexpr uint64_t kPngBytesPerPixel = 4 + sizeof(float);
constexpr uint64_t kExrBytesPerPixel = 8 + sizeof(float);

ScalarTexture loadPng(const std::string& path, TextureChannel channel, uint64_t memoryLimit) {
  const std::string bytes = readInputFile(path, "texture", kMaxImageFileBytes);
  png_image img{};
  img.version = PNG_IMAGE_VERSION;
  if (!png_image_begin_read_from_memory(&img, bytes.data(), bytes.size()))
    throw InputError(path, "", std::string("cannot read PNG: ") + img.message);
  try {
    requireImageMemory(path, img.width, img.height, kPngBytesPerPixel, memoryLimit);
  } catch (...) {
    png_image_free(&img);
    throw;
  }
  img.format = PNG_FORMAT_RGBA;
  std::vector<unsigned char> buf(PNG_IMAGE_SIZE(img));
  if (!png_image_finish_read(&img, nullptr, buf.data(), 0, nullptr))
    throw InputError(path, "", std::string("cannot read PNG: ") + img.message);
  const int w = int(img.width), h = int(img.height);
  std::vector<float> t(size_t(w) * h);
  for (size_t i = 0; i < t.size(); ++i) {
    const unsigned char* p = &buf[4 * i];
    t[i] = pick(channel, p[0] / 255.0f, p[1] / 255.0f, p[2] / 255.0f, p[3] / 255.0f);
  }
  return ScalarTexture(w, h, std::move(t));
}

ScalarTexture loadExr(const std::string& path, TextureChannel channel, uint64_t memoryLimit) {
  ExrInput in(path, "texture");
  requireImageMemory(path, in.width(), in.height(), kExrBytesPerPixel, memoryLimit);
  try {
    const std::unique_ptr<Imf::IStream> stream = in.stream();
    Imf::RgbaInputFile file(*stream);
    const Imath::Box2i dw = file.dataWindow();
    const int w = int(in.width()), h = int(in.height());
    std::vector<Imf::Rgba> px(size_t(w) * h);
    file.setFrameBuffer(px.data() - dw.min.x - int64_t(dw.min.y) * w, 1, size_t(w));
    file.readPixels(dw.min.y, dw.max.y);
    std::vector<float> t(px.size());
    for (size_t i = 0; i < t.size(); ++i) t[i] = pick(channel, px[i].r, px[i].g, px[i].b, px[i].a);
    return ScalarTexture(w, h, std::move(t));
  } catch (const std::exception& e) {
    throw InputError(path, "", std::string("cannot read OpenEXR: ") + e.what());
  }
}

}  // namespace

std::optional<TextureChannel> parseTextureChannel(const std::string& name) {
  if (name == "mean") return TextureChannel::Mean;
  if (name == "r") return TextureChannel::R;
  if (name == "g") return TextureChannel::G;
  if (name == "b") return TextureChannel::B;
  if (name == "a") return TextureChannel::A;
  return std::nullopt;
}

ScalarTexture::ScalarTexture(int width, int height, std::vector<float> texels)
    : w_(width), h_(height), texels_(std::move(texels)) {
  if (w_ <= 0 || h_ <= 0 || texels_.size() != size_t(w_) * size_t(h_))
    throw std::invalid_argument("texture: size does not match its texels");
}

ScalarTexture ScalarTexture::load(const std::string& path, TextureChannel channel, uint64_t memoryLimit) {
  const std::string ext = lowerExtension(path);
  if (ext != "png" && ext != "exr") throw std::runtime_error("unknown image format '." + ext + "' (expected .png or .exr)");
  ScalarTexture t = ext == "png" ? loadPng(path, channel, memoryLimit) : loadExr(path, channel, memoryLimit);
  for (size_t i = 0; i < t.texels_.size(); ++i)
    if (!(t.texels_[i] >= 0.0f && t.texels_[i] <= 1.0f))
      throw std::runtime_error("value " + std::to_string(t.texels_[i]) + " at pixel (" + std::to_string(i % t.w_) +
                               ", " + std::to_string(i / t.w_) + ") is outside [0, 1]");
  return t;
}

size_t ScalarTexture::texelIndex(Vec2 uv) const {
  if (!std::isfinite(uv.x) || !std::isfinite(uv.y)) uv = Vec2(0.0f);
  const float u = uv.x - std::floor(uv.x), v = uv.y - std::floor(uv.y);
  const int x = std::clamp(int(u * float(w_)), 0, w_ - 1);
  const int y = std::clamp(int((1.0f - v) * float(h_)), 0, h_ - 1);
  return size_t(y) * size_t(w_) + size_t(x);
}

}  // namespace kasha
