// libFuzzer target: the PLY check (core/ply_validation.h) with assimp behind it, through
// readPlyMesh, the function the scene loader calls. Bytes are either refused with an error naming
// the file (InputError, MemoryLimitError, or assimp's or kasha's own refusal), or they passed the
// check and become what it declares: every vertex, a triangle or more per face, every index
// inside the positions, every position finite; asked for mesh attributes, a value in [0, 1] per
// vertex or face. The check's rewritten file passes the check
// unchanged. A broken promise, a crash, a hang, an allocation beyond libFuzzer's RSS limit or a
// sanitizer report is a finding.
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>

#include "core/error.h"
#include "core/memory_budget.h"
#include "core/mesh_builders.h"
#include "core/ply_validation.h"
#include "core/shape.h"
#include "tests/fuzz/fuzz_support.h"

namespace {

// A broken promise is a finding.
void require(bool ok, const char* what) { kasha::fuzz::require(ok, "fuzz_ply", what); }

// Well below .ci/fuzz.sh's -rss_limit_mb, so that what the check lets through fits.
constexpr uint64_t kMemoryLimit = uint64_t(256) << 20;

bool namesFile(const std::exception& e) { return std::string(e.what()).find("fuzz.ply") != std::string::npos; }

// The count of an element of the check's rewritten file ("element NAME COUNT" lines, one space).
uint64_t declared(const std::string& checked, const std::string& name) {
  const size_t at = checked.find("\nelement " + name + " ");
  return at == std::string::npos ? 0 : std::stoull(checked.substr(at + name.size() + 10));
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string bytes(reinterpret_cast<const char*>(data), size);
  std::string checked;
  try {
    checked = kasha::validatePly(bytes, "fuzz.ply", kMemoryLimit);
    require(kasha::validatePly(checked, "fuzz.ply", kMemoryLimit) == checked, "the rewritten file is its own rewrite");
  } catch (const kasha::InputError& e) {
    require(std::string(e.what()).rfind("fuzz.ply", 0) == 0, "the message starts with the file");
  } catch (const kasha::MemoryLimitError& e) {
    require(namesFile(e), "the memory message names the file");
  }
  kasha::Shape s;
  try {
    kasha::readPlyMesh(bytes, "fuzz.ply", kMemoryLimit, s);
  } catch (const std::runtime_error& e) {  // the check's errors, assimp's refusal, kasha's checks
    require(namesFile(e), "the message names the file");
    return 0;
  }
  require(!checked.empty(), "only checked bytes are read");
  require(s.positions.size() == declared(checked, "vertex"), "every vertex read");
  require(s.indices.size() % 3 == 0 && s.indices.size() / 3 >= declared(checked, "face"), "a triangle or more per face");
  for (const uint32_t i : s.indices) require(i < s.positions.size(), "indices inside the positions");
  for (const kasha::Vec3& p : s.positions)
    require(std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z), "finite positions");
  require(s.cornerUvs.empty() || s.cornerUvs.size() == s.indices.size(), "a texture coordinate per corner or none");
  // Mesh attributes, where the file has them: one value per vertex or triangle, each in [0, 1].
  kasha::Shape a;
  try {
    kasha::readPlyMesh(bytes, "fuzz.ply", kMemoryLimit, a, {"vertex_color", "face_color"});
  } catch (const std::runtime_error& e) {
    require(namesFile(e), "the attribute message names the file");
    return 0;
  }
  require(a.attributes.size() == 2, "both attributes read");
  for (const kasha::MeshAttribute& m : a.attributes) {
    require(m.values.size() == (m.perFace() ? a.indices.size() / 3 : a.positions.size()), "a value per vertex or face");
    for (const kasha::Vec3& v : m.values)
      for (int k = 0; k < 3; ++k) require(v[k] >= 0.0f && v[k] <= 1.0f, "attribute values in [0, 1]");
  }
  return 0;
}
