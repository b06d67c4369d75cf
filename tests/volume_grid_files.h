#pragma once
// Tests of Mitsuba's .vol grids (core/volume_grid.h): the bytes of a file, written field by field,
// so that a test can also write a header that lies.
#include <array>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

namespace kasha::test {

inline void appendLittleEndian(std::string& out, uint32_t bits) {
  for (int k = 0; k < 4; ++k) out += char((bits >> (8 * k)) & 0xff);
}

inline void appendFloat(std::string& out, float f) {
  uint32_t bits;
  std::memcpy(&bits, &f, 4);
  appendLittleEndian(out, bits);
}

// "VOL", version, encoding, resolution, channels, box (xmin, ymin, zmin, xmax, ymax, zmax), values.
inline std::string volBytes(std::array<int32_t, 3> resolution, int32_t channels, const std::vector<float>& values,
                            std::array<float, 6> box = {0, 0, 0, 1, 1, 1}, int version = 3, int32_t encoding = 1) {
  std::string out = "VOL";
  out += char(version);
  appendLittleEndian(out, uint32_t(encoding));
  for (int32_t n : resolution) appendLittleEndian(out, uint32_t(n));
  appendLittleEndian(out, uint32_t(channels));
  for (float f : box) appendFloat(out, f);
  for (float f : values) appendFloat(out, f);
  return out;
}

}  // namespace kasha::test
