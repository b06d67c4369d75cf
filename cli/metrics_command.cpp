#include "cli/metrics_command.h"

#include <cstdio>
#include <cstring>
#include <stdexcept>

#include <nlohmann/json.hpp>

#include "core/error.h"
#include "core/image_output.h"
#include "core/output_file.h"
#include "integrators/comparison.h"

namespace kasha {
namespace {

// Portable Float Map, greyscale ("Pf"): a text header "Pf\n<w> <h>\n-1.0\n" (negative scale:
// little-endian) and then float32 rows from the bottom of the image to the top.
void writePfm(const std::string& path, int width, int height, const std::vector<float>& values) {
  std::string data = "Pf\n" + std::to_string(width) + " " + std::to_string(height) + "\n-1.0\n";
  static_assert(sizeof(float) == 4);
  const uint16_t probe = 1;
  if (*reinterpret_cast<const uint8_t*>(&probe) != 1) throw std::runtime_error("PFM output needs a little-endian host");
  for (int y = height - 1; y >= 0; --y)
    data.append(reinterpret_cast<const char*>(values.data() + size_t(y) * width), sizeof(float) * size_t(width));
  writeTextFile(path, data);
}

}  // namespace

int runMetrics(const MetricsArgs& a) {
  const XyzImage image = readExrXyz(a.image);
  const XyzImage reference = readExrXyz(a.reference);
  if (!a.errorMap.empty()) checkOutputs({{a.errorMap, "--error-map", ".pfm", ""}});
  ImageError e;
  try {
    e = compareImages(image, reference);
  } catch (const std::invalid_argument& ex) {
    throw InputError(a.image, "", ex.what());
  }
  if (!a.errorMap.empty()) writePfm(a.errorMap, image.width, image.height, relativeErrorMap(image, reference));
  const nlohmann::json j = {{"image", a.image}, {"reference", a.reference}, {"width", image.width},
                            {"height", image.height}, {"rmse", e.rmse}, {"relmse", e.relMse}};
  std::printf("%s\n", j.dump().c_str());
  return 0;
}

}  // namespace kasha
