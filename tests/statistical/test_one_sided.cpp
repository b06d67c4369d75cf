// One-sided materials ("one_sided": true; Mitsuba's diffuse, conductors and plastics) in every
// integrator (docs/scene-format.md "Materials"): a sheet whose front faces the camera and the
// light renders as the two-sided sheet does, pixel by pixel within 4 standard errors
// (tests/pixel_relations.h); turned round (its back to both) it renders exactly black, where the
// two-sided sheet is lit.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>

#include "tests/pixel_relations.h"

namespace kasha {
namespace {

const std::string kTwoSided = R"({"type": "lambertian", "reflectance": 0.9})";
const std::string kOneSided = R"({"type": "lambertian", "reflectance": 0.9, "one_sided": true})";

// The sheet of tests/pixel_relations.h, with its normal turned away from the camera and the light.
std::string backwardSheet(const std::string& sheet) {
  std::string json = test::sheetScene(sheet, test::kSheetPointLight);
  const std::string key = R"("material": "sheet")";
  return json.replace(json.find(key), key.size(), key + R"(, "flip_normals": true)");
}

TEST(OneSided, FrontScattersAsTheTwoSidedSheetAndBackIsBlack) {
  for (const std::string integrator : {"pt", "lt", "bdpt", "ppm", "vcm"}) {
    const int spp = integrator == "lt" ? 128 : 16;
    const std::vector<double> twoSided = test::renderY(test::sheetScene(kTwoSided, test::kSheetPointLight), integrator, spp);
    test::expectCombination(test::renderY(test::sheetScene(kOneSided, test::kSheetPointLight), integrator, spp),
                            {{1.0, &twoSided}}, integrator, 0.05);
    const std::vector<double> back = test::renderY(backwardSheet(kOneSided), integrator, spp);
    EXPECT_TRUE(std::all_of(back.begin(), back.end(), [](double y) { return y == 0.0; })) << integrator;
    const std::vector<double> twoSidedBack = test::renderY(backwardSheet(kTwoSided), integrator, spp);
    EXPECT_GT(*std::max_element(twoSidedBack.begin(), twoSidedBack.end()), 0.0) << integrator;
  }
}

}  // namespace
}  // namespace kasha
