// libFuzzer target: the strict OBJ pass (core/obj_validation.h) with tinyobjloader behind it, as
// the scene loader uses them. Text is either refused with an InputError naming "file:line", or
// what tinyobjloader makes of it keeps the strict pass's promises: every position and texture
// coordinate finite, every index of every face inside the arrays it indexes. A broken promise,
// a crash or a sanitizer report is a finding.
#include <tiny_obj_loader.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "core/error.h"
#include "core/obj_validation.h"
#include "tests/fuzz/fuzz_support.h"

namespace {

// A broken promise is a finding.
void require(bool ok, const char* what) { kasha::fuzz::require(ok, "fuzz_obj", what); }

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  std::string text(reinterpret_cast<const char*>(data), size);
  try {
    text = kasha::validateObjText(text, "fuzz.obj");
  } catch (const kasha::InputError& e) {
    require(std::string(e.what()).rfind("fuzz.obj:", 0) == 0, "the message names the file and line");
    return 0;
  }
  tinyobj::ObjReaderConfig cfg;
  cfg.triangulate = true;
  cfg.vertex_color = false;
  tinyobj::ObjReader reader;
  if (!reader.ParseFromString(text, "", cfg)) return 0;
  const tinyobj::attrib_t& a = reader.GetAttrib();
  for (const float v : a.vertices) require(std::isfinite(v), "finite positions");
  for (const float v : a.texcoords) require(std::isfinite(v), "finite texture coordinates");
  for (const float v : a.normals) require(std::isfinite(v), "finite normals");
  for (const tinyobj::shape_t& s : reader.GetShapes())
    for (const tinyobj::index_t& i : s.mesh.indices) {
      require(i.vertex_index >= 0 && 3 * size_t(i.vertex_index) + 2 < a.vertices.size(), "vertex index in range");
      require(i.texcoord_index < 0 || 2 * size_t(i.texcoord_index) + 1 < a.texcoords.size(), "texcoord index in range");
      require(i.normal_index < 0 || 3 * size_t(i.normal_index) + 2 < a.normals.size(), "normal index in range");
    }
  return 0;
}
