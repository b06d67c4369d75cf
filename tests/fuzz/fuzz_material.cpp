// libFuzzer target: a material file (materials/material_json.h, type "file") on arbitrary bytes.
// The file is read like any scene input and may name further files in tests/fuzz/data (a CSV, a
// matrix, an image) or itself: it loads, or it is refused with an InputError naming the scene
// file's material or, for a problem inside the material file, that file; a cycle or a deep
// chain must be refused, not recursed into. Anything else is a finding.
#include <cstdio>
#include <cstdlib>
#include <string>

#include <nlohmann/json.hpp>

#include "core/error.h"
#include "materials/material_json.h"
#include "tests/fuzz/fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace kasha;
  const std::string dir = fuzz::scratchDirectory();
  fuzz::writeInput("material.json", data, size);
  SpectrumContext ctx("scene.json", dir);
  ctx.memoryLimit = uint64_t(64) << 20;
  const WavelengthRange range{360.0f, 830.0f};
  ctx.range = &range;
  try {
    parseMaterial(nlohmann::json{{"type", "file"}, {"file", "material.json"}}, ctx, "/materials/m", range);
  } catch (const InputError& e) {
    const std::string msg = e.what();
    if (msg.rfind("scene.json: /materials/m", 0) != 0 && msg.rfind(dir + "/material.json: ", 0) != 0) {
      std::fprintf(stderr, "fuzz_material: the message names neither the scene's material nor the file: %s\n", e.what());
      std::abort();
    }
  }
  return 0;
}
