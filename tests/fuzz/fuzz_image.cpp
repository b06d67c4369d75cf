// libFuzzer target: image input (core/texture.h, core/image_input.h) on arbitrary bytes, as a
// PNG when they start with PNG's signature and as an OpenEXR otherwise, both as a texture and
// (OpenEXR) as a render read back (its XYZ layer, or its S0.<λ> spectral channels integrated).
// An image is refused with an exception naming it, or decodes
// to texels in [0, 1] (textures) and finite XYZ pixels (renders); the memory limit is 256 KiB
// (some 20 000 pixels: decoding more only slows the fuzzer down), so a header
// declaring more pixels must be refused before decoding (-rss_limit_mb catches a miss).
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

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace kasha;
  const bool png = size >= 8 && std::memcmp(data, "\x89PNG\r\n\x1a\n", 8) == 0;
  const std::string path = fuzz::writeInput(png ? "fuzz.png" : "fuzz.exr", data, size);
  try {
    const auto t = TextureLoader(kLimit).load(path, TextureChannel::Mean, TextureWrap::Repeat, TextureFilter::Bilinear);
    require(t->width() > 0 && t->height() > 0, "a texture has pixels");
    for (size_t i = 0; i < size_t(t->width()) * size_t(t->height()); ++i)
      require(t->texel(i) >= 0.0f && t->texel(i) <= 1.0f, "texels in [0, 1]");
  } catch (const std::runtime_error& e) {  // InputError, or the texture's own reasons
    require(std::strlen(e.what()) > 0, "a reason");
  }
  if (png) return 0;
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
