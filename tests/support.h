#pragma once
// Helpers shared by the tests: paths into the source tree and batch statistics.
#include <cmath>
#include <string>
#include <vector>

namespace kasha::test {

inline std::string sourcePath(const std::string& rel) { return std::string(KASHA_SOURCE_DIR) + "/" + rel; }

// A camera, one lambertian material and one emissive rectangle: the smallest valid scene (JSON).
inline constexpr const char* kMinimalScene = R"({
  "camera": {"position": [0, 0, -3], "look_at": [0, 0, 0], "fov": 40, "resolution": [8, 8]},
  "materials": {"white": {"type": "lambertian", "reflectance": 0.5}},
  "shapes": [{"type": "rectangle", "center": [0, 0, 0], "u": [1, 0, 0], "v": [0, 1, 0],
              "material": "white", "emission": {"radiance": 1}}]
})";

// Mean and standard error of the mean of independent batch estimates.
struct BatchStats {
  double mean = 0.0, stderr_ = 0.0;
};
BatchStats batchStats(const std::vector<double>& batches);

// Pearson's χ² test of observed counts against expected counts, pooling cells with expected < 5
// (the method of pbrt's and Mitsuba's sampling tests). Returns the p-value.
double chi2PValue(const std::vector<double>& observed, const std::vector<double>& expected);

}  // namespace kasha::test
