#pragma once
// `kasha compare`: one scene, several integrators, the same wall-clock time (or the same samples
// per pixel) each, and each one's RMSE against a reference image.
#include <string>
#include <vector>

namespace kasha {

struct CompareArgs {
  std::string scene, reference, csv;
  std::vector<std::string> integrators{"pt", "lt", "bdpt-shared", "bdpt-independent"};
  double time = 0.0;  // seconds per integrator (0: use spp)
  int spp = 0;
  int threads = 0;
  int64_t seed = 1;
  double referenceTime = 60.0;  // when the reference must be rendered first
  std::string referenceIntegrator = "pt";
};

// Prints a table and writes the CSV; returns the exit code. Throws InputError on bad input.
int runCompare(const CompareArgs& args);

}  // namespace kasha
