// Opacity masks (materials/opacity_mask.h) in every integrator (docs/validation.md §2):
// - a mask of opacity 1 is its nested material, rendered bit for bit;
// - a sheet seen under a point light reflects α times what the unmasked sheet does (the nested
//   f scaled by α; every integrator sees it through eval), within 4 standard errors;
// - an emitter seen through a black sheet of opacity α shows (1 − α) of its radiance (the
//   pass-through, sampled as a specular direction), within 4 standard errors. Light tracing has no
//   camera-path strategy, so it cannot see through a delta pass-through (as through thin glass).
#include <gtest/gtest.h>

#include <cmath>

#include "core/error.h"
#include "materials/opacity_mask.h"
#include "tests/pixel_relations.h"

namespace kasha {
namespace {

using test::kSheetPointLight;
using test::mean;
using test::renderY;
using test::sheetScene;

// An emitter at z = −1 facing the camera, filling the view behind the sheet.
const std::string kEmitterBehind =
    R"(, {"type": "rectangle", "corners": [[-3,-3,-1], [3,-3,-1], [3,3,-1], [-3,3,-1]], "material": "black",
          "emission": {"radiance": "D65", "scale": 1}}], "lights": [])";

const std::string kGlossy = R"({"type": "rough_conductor", "reflectance": 0.8, "alpha": 0.3})";
const std::string kWhite = R"({"type": "lambertian", "reflectance": 0.9})";
std::string mask(float opacity, const std::string& nested) {
  return R"({"type": "mask", "opacity": )" + std::to_string(opacity) + R"(, "material": )" + nested + "}";
}

const char* kIntegrators[] = {"pt", "lt", "bdpt", "ppm", "vcm"};

TEST(OpacityMask, OpaqueMaskIsTheNestedMaterial) {
  for (const std::string& nested : {kGlossy, kWhite})
    for (const char* integ : {"pt", "lt", "bdpt"}) {
      const std::vector<double> plain = renderY(sheetScene(nested, kSheetPointLight), integ, 2);
      EXPECT_GT(mean(plain), 0.0) << integ << ": the scene is lit";
      EXPECT_EQ(renderY(sheetScene(mask(1.0f, nested), kSheetPointLight), integ, 2), plain) << integ << " " << nested;
    }
}

// got ≈ ratio·reference pixel by pixel (tests/pixel_relations.h).
void expectRatio(const std::vector<double>& got, const std::vector<double>& reference, double ratio,
                 const std::string& what, double resolution) {
  test::expectCombination(got, {{ratio, &reference}}, what, resolution);
}

TEST(OpacityMask, MaskedSheetReflectsOpacityTimesTheNestedMaterial) {
  const float alpha = 0.375f;
  for (const std::string integ : kIntegrators) {
    const int spp = integ == "lt" ? 512 : 64;  // light tracing splats each subpath into one pixel
    expectRatio(renderY(sheetScene(mask(alpha, kWhite), kSheetPointLight), integ, spp),
                renderY(sheetScene(kWhite, kSheetPointLight), integ, spp), alpha, integ, 0.05);
  }
}

TEST(OpacityMask, EmitterSeenThroughTheMask) {
  const float alpha = 0.3f;
  for (const char* integ : {"pt", "bdpt", "ppm", "vcm"})
    expectRatio(renderY(sheetScene(mask(alpha, R"({"type": "lambertian", "reflectance": 0})"), kEmitterBehind), integ, 32),
                renderY(sheetScene(mask(0.0f, kWhite), kEmitterBehind), integ, 8), 1.0 - alpha, integ, 0.05);
}

// A small emitter behind a masked white sheet: the pass-through, a delta of a Bsdf with smooth
// lobes, is a path that no connection at the sheet can make, so the bidirectional integrators must
// not weigh it against one (BsdfFlags::DeltaLobe; bdpt rendered 0.73 of it when they did).
TEST(OpacityMask, SmallEmitterSeenThroughAMaskedWhiteSheet) {
  const std::string smallEmitterBehind =
      R"(, {"type": "rectangle", "corners": [[-0.3,-0.3,-1], [0.3,-0.3,-1], [0.3,0.3,-1], [-0.3,0.3,-1]], "material": "black",
            "emission": {"radiance": "D65", "scale": 1}}], "lights": [])";
  const float alpha = 0.3f;
  // The reference is path tracing's, which weighs next-event estimation by the event it sampled.
  const std::vector<double> clear = renderY(sheetScene(mask(0.0f, kWhite), smallEmitterBehind), "pt", 256);
  for (const char* integ : {"pt", "bdpt", "vc", "vcm"})
    expectRatio(renderY(sheetScene(mask(alpha, kWhite), smallEmitterBehind), integ, 256), clear, 1.0 - alpha, integ, 0.05);
}

TEST(OpacityMask, ClearErrors) {
  const auto error = [](const std::string& sheet) -> std::string {
    try {
      loadSceneFromString(sheetScene(sheet, kSheetPointLight), "mask.json");
    } catch (const InputError& e) {
      return e.what();
    }
    return "no error";
  };
  EXPECT_EQ(error(R"({"type": "mask", "opacity": 1.5, "material": )" + kWhite + "}"),
            "mask.json: /materials/sheet/opacity: must lie in [0, 1]");
  EXPECT_EQ(error(R"({"type": "mask", "material": )" + kWhite + "}"),
            "mask.json: /materials/sheet/opacity: missing required field");
  EXPECT_EQ(error(R"({"type": "mask", "opacity": 0.5, "material": {"type": "normal_map", "normals": "n.png", "material": )" +
                  kWhite + "}}")
                .find("mask.json: /materials/sheet/material/normals:"),
            0u)
      << "the nested material's own errors first";
}

}  // namespace
}  // namespace kasha
