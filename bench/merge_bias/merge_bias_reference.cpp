// Prints, as JSON, the closed form of a point-lit plane scene (tests/point_lit_plane.h) and the image
// vertex merging converges to after each given number of passes with first radius r_1 and α:
//   merge_bias_reference SCENE.json R1 ALPHA PASSES...
// {"exact": [X, Y, Z], "passes": {"P": {"radius": r_P, "blurred": [X, Y, Z]}, ...}}
// for bench/merge_bias/merge_bias.py, which compares `bpm` and `vcm` renders with them.
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>

#include "scene/scene_loader.h"
#include "tests/point_lit_plane.h"

int main(int argc, char** argv) {
  if (argc < 5) {
    std::fprintf(stderr, "usage: %s SCENE.json R1 ALPHA PASSES...\n", argv[0]);
    return 2;
  }
  try {
    const auto scene = kasha::loadScene(argv[1]);
    const kasha::test::PointLitPlane p = kasha::test::pointLitPlane(*scene);
    const float r1 = std::strtof(argv[2], nullptr), alpha = std::strtof(argv[3], nullptr);
    const kasha::Vec3 exact = kasha::test::exactMeanXyz(p);
    std::printf("{\"exact\": [%.9g, %.9g, %.9g], \"passes\": {", exact.x, exact.y, exact.z);
    for (int k = 4; k < argc; ++k) {
      const int passes = std::atoi(argv[k]);
      const kasha::Vec3 b = kasha::test::mergedMeanXyz(p, r1, alpha, passes);
      std::printf("%s\"%d\": {\"radius\": %.6g, \"blurred\": [%.9g, %.9g, %.9g]}", k > 4 ? ", " : "", passes,
                  std::sqrt(kasha::progressiveRadiusSquared(r1, alpha, passes)), b.x, b.y, b.z);
    }
    std::printf("}}\n");
  } catch (const std::exception& e) {
    std::fprintf(stderr, "merge_bias_reference: %s\n", e.what());
    return 1;
  }
  return 0;
}
