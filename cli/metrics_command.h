#pragma once
// `kasha metrics IMAGE.exr REFERENCE.exr`: the error of one render against a reference, as JSON on
// standard output (for scripts such as bench/convergence/), optionally with a per-pixel error map.
#include <string>

namespace kasha {

struct MetricsArgs {
  std::string image, reference;
  std::string errorMap;  // PFM file for the per-pixel relative squared error (empty: none)
};

// Prints {"image", "reference", "width", "height", "rmse", "relmse"}; returns the exit code.
// Throws InputError naming the file on unreadable or mismatched images.
int runMetrics(const MetricsArgs& args);

}  // namespace kasha
