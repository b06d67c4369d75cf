// Blends (materials/blend.h) in every integrator (docs/validation.md §2): a sheet of
// blend(A, B, w) renders (1 − w) times the sheet of A plus w times the sheet of B, pixel by pixel
// within 4 standard errors (tests/pixel_relations.h), for
// - a Lambertian and a rough conductor under a point light (every integrator sees both lobes
//   through eval and sampling);
// - a mirror and a Lambertian under a large emitter that the mirror shows to the camera (the
//   mirror's delta, sampled as a specular direction of a Bsdf that is not all deltas, with its own
//   path weight; the Lambertian by next-event estimation and photons). Light tracing has no
//   camera-path strategy and cannot see a delta reflection, so it is left out there. bdpt and vc
//   weigh the sampled delta only against strategies that can make it (PathVertex::joinable): when
//   they took connectibility from the Bsdf's flags, they rendered 0.88 of the expectation here.
#include <gtest/gtest.h>

#include <string>

#include "tests/pixel_relations.h"

namespace kasha {
namespace {

using test::kSheetPointLight;
using test::sheetScene;

// An emitter at z = 3 (behind the camera) facing the sheet, which the mirror reflects into view.
const std::string kEmitterAbove =
    R"(, {"type": "rectangle", "corners": [[-3,-3,3], [-3,3,3], [3,3,3], [3,-3,3]], "material": "black",
          "emission": {"radiance": "D65", "scale": 1}}], "lights": [])";

const std::string kWhite = R"({"type": "lambertian", "reflectance": 0.9})";
const std::string kGlossy = R"({"type": "rough_conductor", "reflectance": 0.8, "alpha": 0.3})";
const std::string kMirror = R"({"type": "mirror", "reflectance": 0.8})";
std::string blend(const std::string& first, const std::string& second, double weight) {
  return R"({"type": "blend", "weight": )" + std::to_string(weight) + R"(, "materials": [)" + first + ", " + second + "]}";
}

// The blended sheet against its components' sheets, each rendered by `integrator` at `spp`.
void expectBlendOfSheets(const std::string& first, const std::string& second, double weight, const std::string& rest,
                         const std::string& integrator, int spp) {
  const std::vector<double> a = test::renderY(sheetScene(first, rest), integrator, spp);
  const std::vector<double> b = test::renderY(sheetScene(second, rest), integrator, spp);
  test::expectCombination(test::renderY(sheetScene(blend(first, second, weight), rest), integrator, spp),
                          {{1.0 - weight, &a}, {weight, &b}}, integrator, 0.05);
}

TEST(Blend, DiffuseAndGlossySheet) {
  for (const std::string integrator : {"pt", "lt", "bdpt", "ppm", "vcm"})
    expectBlendOfSheets(kWhite, kGlossy, 0.3, kSheetPointLight, integrator, integrator == "lt" ? 256 : 32);
}

TEST(Blend, MirrorAndDiffuseSheet) {
  for (const std::string integrator : {"pt", "bdpt", "vc", "ppm", "vcm"})
    expectBlendOfSheets(kMirror, kWhite, 0.4, kEmitterAbove, integrator, 32);
}

}  // namespace
}  // namespace kasha
