// libFuzzer target: image input (core/texture.h, core/image_input.h) on arbitrary bytes, named
// by their signature (PNG, JPEG, BMP, Radiance HDR, OpenEXR; TGA, which has none, otherwise) so
// that each decoder family (core/stb_image_input.h, core/exr_input.h) is reached: as a texture,
// and (OpenEXR) as a render read back (its XYZ layer, or its S0.<λ> spectral channels
// integrated). An image is refused with an exception naming it, or decodes to texels in [0, 1]
// (textures) and finite XYZ pixels (renders); the memory limit is 256 KiB (some 20 000 pixels:
// decoding more only slows the fuzzer down), so a header declaring more pixels must be refused
// before decoding (-rss_limit_mb catches a miss).
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <stdexcept>
#include <string>

#include "core/error.h"
#include "core/image_input.h"
#include "core/texture.h"
#include "tests/fuzz/fuzz_support.h"

namespace {

// A broken promise is a finding.
void require(bool ok, const char* what) { kasha::fuzz::require(ok, "fuzz_image", what); }

constexpr uint64_t kLimit = uint64_t(256) << 10;

// The file name whose extension matches the bytes' signature.
const char* nameFor(const uint8_t* data, size_t size) {
  const auto starts = [&](const char* s, size_t n) { return size >= n && std::memcmp(data, s, n) == 0; };
  if (starts("\x89PNG\r\n\x1a\n", 8)) return "fuzz.png";
  if (starts("\xFF\xD8", 2)) return "fuzz.jpg";
  if (starts("BM", 2)) return "fuzz.bmp";
  if (starts("#?", 2)) return "fuzz.hdr";
  if (starts("\x76\x2f\x31\x01", 4)) return "fuzz.exr";
  return "fuzz.tga";
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace kasha;
  const char* name = nameFor(data, size);
  const std::string path = fuzz::writeInput(name, data, size);
  try {
    const auto t = TextureLoader(kLimit).load(path, TextureChannel::Mean, TextureWrap::Repeat, TextureFilter::Bilinear);
    require(t->width() > 0 && t->height() > 0, "a texture has pixels");
    for (size_t i = 0; i < size_t(t->width()) * size_t(t->height()); ++i)
      require(t->texel(i) >= 0.0f && t->texel(i) <= 1.0f, "texels in [0, 1]");
  } catch (const std::runtime_error& e) {  // InputError, or the texture's own reasons
    require(std::strlen(e.what()) > 0, "a reason");
  }
  if (std::strcmp(name, "fuzz.exr") != 0) return 0;
  try {
    const XyzImage img = readExrXyz(path, kLimit);
    require(img.pixels.size() == size_t(img.width) * size_t(img.height), "one pixel per texel");
    for (const auto& p : img.pixels)
      require(std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z), "finite pixels");
  } catch (const InputError& e) {
    require(std::string(e.what()).rfind(path, 0) == 0, "the message names the file");
  }
  return 0;
}
