#include "cli/matrix_command.h"

#include <cmath>
#include <cstdio>
#include <iostream>
#include <sstream>
#include <vector>

#include "cli/option_checks.h"
#include "core/error.h"
#include "core/image_output.h"
#include "core/memory_budget.h"
#include "core/output_file.h"
#include "materials/jung_bbrrdf.h"
#include "scene/scene_loader.h"

namespace kasha {

CLI::App* addMatrixCommand(CLI::App& app, MatrixArgs& ma) {
  CLI::App* matrix = app.add_subcommand("matrix", "Export a fluorescent material's reradiation matrix (Jung18 eq. 5) as CSV");
  matrix->add_option("scene", ma.scene, "Scene file (JSON)")->required();
  matrix->add_option("--material", ma.material, "Material name")->required();
  matrix->add_option("--step", ma.step, "Grid step in nm (default 5)")->check(numberCheck(Sign::Positive, false));
  matrix->add_option("-o,--output", ma.output, "CSV output (default: standard output)");
  matrix->add_option("--memory-limit", ma.memoryLimit, "Largest buffer kasha may allocate (default 8G)")->check(kByteSize);
  return matrix;
}

int runMatrix(const MatrixArgs& a) {
  const uint64_t memoryLimit = parseByteSize(a.memoryLimit);
  SceneLoadOptions load;
  load.memoryLimit = memoryLimit;
  std::unique_ptr<Scene> scene = loadScene(a.scene, load);
  size_t idx = 0;
  while (idx < scene->materialNames.size() && scene->materialNames[idx] != a.material) ++idx;
  if (idx == scene->materialNames.size())
    throw UsageError("--material", a.material, "no material of that name in " + a.scene);
  const auto* jung = dynamic_cast<const JungBbrrdf*>(scene->materials[idx].get());
  if (!jung) throw UsageError("--material", a.material, "not a jung_fluorescent material in " + a.scene);
  if (!a.output.empty()) checkOutputs({{a.output, "-o", "", ""}});
  // Grid points min + i·step up to max (1e-3 nm tolerance); counted in double, so a tiny step is
  // a clear memory error rather than an endless float loop.
  const double span = double(scene->range.max) + 1e-3 - double(scene->range.min);
  const double count = std::floor(span / double(a.step)) + 1.0;
  const uint64_t n = count < 1e9 ? uint64_t(count) : uint64_t(1e9);
  // The matrix in floats plus its CSV text (about 12 characters an entry).
  requireMemory(saturatingMul(saturatingMul(n, n), sizeof(float) + 12),
                "a " + std::to_string(n) + "x" + std::to_string(n) + " matrix (--step " + std::to_string(a.step) + ")",
                memoryLimit);
  std::vector<float> grid;
  for (uint64_t i = 0; i < n; ++i) grid.push_back(float(double(scene->range.min) + double(i) * double(a.step)));
  const ReradiationMatrix m = jung->reradiationMatrix(grid);
  std::ostringstream out;
  out << "# Reradiation matrix (Jung18 eq. 5) of material '" << a.material << "' in " << a.scene << "\n";
  out << "# Rows: input wavelength; columns out_<nm>: output wavelength; each entry is the energy fraction per band.\n";
  out << "wavelength_in_nm";
  for (float l : grid) out << ",out_" << l;
  out << "\n";
  for (size_t i = 0; i < grid.size(); ++i) {
    out << grid[i];
    for (float v : m.m[i]) out << "," << v;
    out << "\n";
  }
  if (a.output.empty()) {
    std::cout << out.str();
  } else {
    writeTextFile(a.output, out.str());
    std::printf("wrote %s (%zu x %zu)\n", a.output.c_str(), grid.size(), grid.size());
  }
  return 0;
}

}  // namespace kasha
