#include "core/stb_image_input.h"

#include <climits>
#include <memory>

#include "core/error.h"
#include "core/input_file.h"
#include "core/stb_guard.h"
#include "core/memory_budget.h"

// stb_image's implementation, restricted to the formats kasha reads.
#define STB_IMAGE_IMPLEMENTATION
#define STB_IMAGE_STATIC
#define STBI_NO_STDIO
#define STBI_ONLY_PNG
#define STBI_ONLY_BMP
#define STBI_ONLY_TGA
#define STBI_ONLY_HDR
#define STBI_FAILURE_USERMSG
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"
#pragma GCC diagnostic ignored "-Wsign-compare"
#pragma GCC diagnostic ignored "-Wunused-function"
#include <stb/stb_image.h>
#pragma GCC diagnostic pop

namespace kasha {
namespace {

const stbi_uc* stbBytes(const std::string& bytes) { return reinterpret_cast<const stbi_uc*>(bytes.data()); }

}  // namespace

StbImageInput::StbImageInput(const std::string& path, const std::string& what, const std::string& format,
                             const std::string& signature)
    : path_(path), format_(format), bytes_(readInputFile(path, what, kMaxImageFileBytes)) {
  if (bytes_.compare(0, signature.size(), signature) != 0)
    throw InputError(path, "", "cannot read " + format + ": not " + format + " (its signature is missing)");
  if (bytes_.size() > size_t(INT_MAX)) throw InputError(path, "", "cannot read " + format + ": larger than 2 GiB");
  checkPngChunks(bytes_, path);  // before stb reads a chunk
  const int length = int(bytes_.size());
  int w = 0, h = 0, channels = 0;
  // stbi_info tries every format and reports only that none fits; its decoders refuse an image
  // of more than 2^30 bytes (stbi__mad3sizes_valid, PNG's header check) before allocating.
  if (!stbi_info_from_memory(stbBytes(bytes_), length, &w, &h, &channels) || w <= 0 || h <= 0)
    throw InputError(path, "", "cannot read " + format + ": corrupt, not " + format +
                                   ", or larger than stb_image decodes (2^30 bytes)");
  width_ = uint64_t(w);
  height_ = uint64_t(h);
  linear_ = stbi_is_hdr_from_memory(stbBytes(bytes_), length) != 0;
  if (linear_) checkHdrRuns(bytes_, width_, height_, path);  // before stb decodes the pixels
  sixteenBit_ = stbi_is_16_bit_from_memory(stbBytes(bytes_), length) != 0;
}

uint64_t StbImageInput::decodeBytes() const {
  const uint64_t sample = linear_ ? sizeof(float) : sixteenBit_ ? 2 : 1;
  return saturatingMul(saturatingMul(width_, height_), 2 * 4 * sample);
}

void StbImageInput::decode(const PixelVisitor& pixel) const {
  int w = 0, h = 0, channels = 0;
  const int length = int(bytes_.size());
  const auto check = [&](const void* decoded) {
    // The header was read by stbi_info_from_memory; the decoder reads it again.
    if (!decoded) throw InputError(path_, "", "cannot read " + format_ + ": " + stbi_failure_reason());
    if (uint64_t(w) != width_ || uint64_t(h) != height_)
      throw InputError(path_, "", "cannot read " + format_ + ": the decoded size differs from the header's");
  };
  const auto visit = [&](const auto* rgba, float maxCode) {  // a division, so that the largest code is exactly 1
    for (size_t i = 0, n = size_t(w) * size_t(h) * 4; i < n; i += 4)
      pixel(float(rgba[i]) / maxCode, float(rgba[i + 1]) / maxCode, float(rgba[i + 2]) / maxCode, float(rgba[i + 3]) / maxCode);
  };
  if (linear_) {
    const std::unique_ptr<float, void (*)(void*)> px(stbi_loadf_from_memory(stbBytes(bytes_), length, &w, &h, &channels, 4),
                                                    stbi_image_free);
    check(px.get());
    visit(px.get(), 1.0f);
  } else if (sixteenBit_) {
    const std::unique_ptr<stbi_us, void (*)(void*)> px(
        stbi_load_16_from_memory(stbBytes(bytes_), length, &w, &h, &channels, 4), stbi_image_free);
    check(px.get());
    visit(px.get(), 65535.0f);
  } else {
    const std::unique_ptr<stbi_uc, void (*)(void*)> px(stbi_load_from_memory(stbBytes(bytes_), length, &w, &h, &channels, 4),
                                                      stbi_image_free);
    check(px.get());
    visit(px.get(), 255.0f);
  }
}

}  // namespace kasha
