// libFuzzer target: Mitsuba's .vol grids (core/volume_grid.h), from bytes and from a file. Bytes
// are either refused with one line naming the file (InputError, MemoryLimitError), or they become
// what the reader promises: a resolution of at least one cell per axis, 1, 3 or 6 channels, the
// same grid by either path, and lookups (in every wrap mode) that are finite, not negative and
// bounded by the channel's maximum. A broken promise, a crash, a hang, an allocation beyond
// libFuzzer's RSS limit or a sanitizer report is a finding.
#include <cfloat>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>

#include "core/volume_grid.h"
#include "tests/fuzz/fuzz_support.h"

namespace {

void require(bool ok, const char* what) { kasha::fuzz::require(ok, "fuzz_volume_grid", what); }

// Well below .ci/fuzz.sh's -rss_limit_mb, so that what the reader lets through fits.
constexpr uint64_t kMemoryLimit = uint64_t(256) << 20;

void requireOneLine(const std::runtime_error& e) {
  const std::string message = e.what();
  require(message.find("fuzz.vol") != std::string::npos, "the message names the file");
  require(message.find('\n') == std::string::npos, "the message is one line");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string bytes(reinterpret_cast<const char*>(data), size);
  kasha::VolumeGrid fromBytes, fromFile;
  bool parsed = true, read = true;
  try {
    fromBytes = kasha::VolumeGrid::parse(bytes, "fuzz.vol", kMemoryLimit);
  } catch (const std::runtime_error& e) {  // InputError, MemoryLimitError
    requireOneLine(e);
    parsed = false;
  }
  try {
    fromFile = kasha::VolumeGrid::read(kasha::fuzz::writeInput("fuzz.vol", data, size), kMemoryLimit);
  } catch (const std::runtime_error& e) {
    requireOneLine(e);
    read = false;
  }
  require(parsed == read, "bytes and file are refused alike");
  if (!parsed) return 0;
  const std::array<int, 3> n = fromBytes.resolution();
  require(n[0] >= 1 && n[1] >= 1 && n[2] >= 1, "at least one cell per axis");
  require(fromBytes.channels() == 1 || fromBytes.channels() == 3 || fromBytes.channels() == 6, "1, 3 or 6 channels");
  require(fromFile.resolution() == n && fromFile.channels() == fromBytes.channels(), "the same header by either path");
  for (int c = 0; c < fromBytes.channels(); ++c) {
    require(fromFile.cell(n[0] - 1, n[1] - 1, n[2] - 1, c) == fromBytes.cell(n[0] - 1, n[1] - 1, n[2] - 1, c), "the same last cell");
    for (const kasha::GridWrap wrap : {kasha::GridWrap::Clamp, kasha::GridWrap::Repeat, kasha::GridWrap::Mirror})
      for (const kasha::Vec3 u : {kasha::Vec3(0.5f), kasha::Vec3(-1.0f, 0.3f, 2.0f), kasha::Vec3(0.1f, 0.9f, 0.42f)}) {
        const float v = fromBytes.lookup(u, c, wrap);
        require(std::isfinite(v) && v >= 0.0f, "finite, non-negative lookups");
        // Weights summing to 1 in float, on values that may be subnormal (a few ulps of FLT_MIN).
        require(v <= fromBytes.maximum(c) * (1.0f + 1e-5f) + 4.0f * FLT_MIN, "lookups bounded by the maximum");
      }
  }
  return 0;
}
