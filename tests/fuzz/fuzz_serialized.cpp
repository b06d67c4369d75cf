// libFuzzer target: Mitsuba serialized meshes (core/serialized_mesh.h), meshes 0 and 1 of the
// input. Bytes are either refused with one line naming the file (InputError, MemoryLimitError), or
// they become what the reader promises: three indices per triangle, each below the vertices read,
// finite positions, and corner normals and texture coordinates for every corner or none. A broken
// promise, a crash, a hang, an allocation beyond libFuzzer's RSS limit or a sanitizer report is a
// finding.
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>

#include "core/serialized_mesh.h"
#include "core/shape.h"
#include "tests/fuzz/fuzz_support.h"

namespace {

void require(bool ok, const char* what) { kasha::fuzz::require(ok, "fuzz_serialized", what); }

// Well below .ci/fuzz.sh's -rss_limit_mb, so that what the reader lets through fits.
constexpr uint64_t kMemoryLimit = uint64_t(256) << 20;

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string bytes(reinterpret_cast<const char*>(data), size);
  for (const uint64_t index : {0, 1}) {
    kasha::Shape s;
    try {
      kasha::readSerializedMesh(bytes, "fuzz.serialized", index, kMemoryLimit, s);
    } catch (const std::runtime_error& e) {  // InputError, MemoryLimitError
      const std::string message = e.what();
      require(message.find("fuzz.serialized") != std::string::npos, "the message names the file");
      require(message.find('\n') == std::string::npos, "the message is one line");
      continue;
    }
    require(!s.indices.empty() && s.indices.size() % 3 == 0, "whole triangles");
    for (const uint32_t i : s.indices) require(i < s.positions.size(), "indices inside the positions");
    for (const kasha::Vec3& p : s.positions)
      require(std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z), "finite positions");
    require(s.cornerNormals.empty() || s.cornerNormals.size() == s.indices.size(), "a normal per corner or none");
    require(s.cornerUvs.empty() || s.cornerUvs.size() == s.indices.size(), "a texture coordinate per corner or none");
  }
  return 0;
}
