#pragma once
// `kasha matrix`: the reradiation matrix M = R + c·a·Q·eᵀ (Jung18 eq. 5) of a jung_fluorescent
// material on a wavelength grid, as CSV (docs/cli.md).
#include <CLI/CLI.hpp>

#include <string>

namespace kasha {

struct MatrixArgs {
  std::string scene, material, output;
  float step = 5.0f;
  std::string memoryLimit = "8G";
};

CLI::App* addMatrixCommand(CLI::App& app, MatrixArgs& args);
// Returns the exit code; throws UsageError and InputError.
int runMatrix(const MatrixArgs& args);

}  // namespace kasha
