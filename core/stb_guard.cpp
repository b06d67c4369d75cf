#include "core/stb_guard.h"

#include <cstdint>

#include "core/error.h"

namespace kasha {

void checkPngChunks(const std::string& bytes, const std::string& path) {
  const size_t n = bytes.size();
  if (bytes.compare(0, 8, "\x89PNG\r\n\x1a\n") != 0) return;  // stb's PNG reader needs the signature
  for (size_t p = 8; p + 8 <= n;) {  // length (4, big-endian), type (4), data, CRC (4)
    uint64_t length = 0;
    for (size_t k = 0; k < 4; ++k) length = (length << 8) | uint8_t(bytes[p + k]);
    if (length > n - (p + 8))
      throw InputError(path, "", "cannot read PNG: a chunk declares " + std::to_string(length) + " bytes, more than the file holds");
    if (bytes.compare(p + 4, 4, "IEND") == 0) return;
    p += 12 + length;
  }
}

void checkHdrRuns(const std::string& bytes, uint64_t width, uint64_t height, const std::string& path) {
  // stb's header (stbi__hdr_gettoken): the signature line, then lines up to one that is empty or
  // begins with a NUL byte (stb keeps each line as a C string), then the resolution line
  // ("-Y h +X w"), then the pixels.
  size_t lineEnd = bytes.find('\n');
  for (;;) {
    if (lineEnd == std::string::npos) return;  // stb refuses it
    const size_t lineStart = lineEnd + 1;
    lineEnd = bytes.find('\n', lineStart);
    if (lineStart < bytes.size() && (lineStart == lineEnd || bytes[lineStart] == '\0')) break;
  }
  const size_t resolutionEnd = lineEnd == std::string::npos ? lineEnd : bytes.find('\n', lineEnd + 1);
  if (resolutionEnd == std::string::npos) return;
  // stb decodes widths outside [8, 32768) flat, and a scanline without the RLE header flat from
  // there on: neither loops.
  if (width < 8 || width >= 32768) return;
  const size_t n = bytes.size();
  size_t p = resolutionEnd + 1;
  const auto next = [&]() -> unsigned { return p < n ? uint8_t(bytes[p++]) : (++p, 0u); };  // stb reads 0 past the end
  for (uint64_t j = 0; j < height; ++j) {
    const unsigned c1 = next(), c2 = next(), hi = next();
    if (c1 != 2 || c2 != 2 || (hi & 0x80)) return;
    if (((hi << 8) | next()) != width) return;  // stb refuses it
    for (int k = 0; k < 4; ++k)
      for (uint64_t i = 0; i < width;) {
        unsigned count = next();
        if (count > 128) {
          next();  // the run's value
          count -= 128;
        } else {
          if (count == 0)
            throw InputError(path, "", "cannot read Radiance HDR: a run-length encoded scanline (" + std::to_string(j) +
                                           ") holds a run of length 0, or the data ends early");
          p += count;
        }
        if (count > width - i) return;  // stb refuses it
        i += count;
      }
  }
}

}  // namespace kasha
