// Hero wavelength sampling (pt --hero 4) against single-wavelength path tracing where a Bsdf's
// direction sampling depends on the wavelength (issue 11): a glossy Zhdanov floor whose passive
// part is coloured (gloss 0.5, exponent 20, passive 0 below 480 nm and 0.5 above 520 nm, so the
// gloss lobe is chosen with probability 1 in the blue and 1/2 in the red), a clear coat over
// Jung18's BBRRDF with c = 0, and dispersive rough glass, under an area light large enough that
// next-event estimation and direction sampling share the MIS weight, at 16×16 pixels. Ending the
// secondary wavelengths only after direction sampling (the old hero tracer) fails the Zhdanov
// and coated cases; ending them before next-event estimation (BsdfFlags::
// WavelengthDependentDirection) agrees quadrant by quadrant within 4 standard errors.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "scene/scene_loader.h"
#include "integrators/integrator_factory.h"
#include "tests/region_batches.h"
#include "tests/support.h"

namespace kasha {
namespace {

constexpr int kRes = 16, kBatches = 16;

// The floor (material `surface`) under a 1×1 lamp, with a sphere of `ball` on it.
std::string sceneWith(const std::string& surface, const std::string& ball) {
  return R"({
  "render": {"max_depth": 6},
  "camera": {"position": [0, 2, -3], "look_at": [0, 0.2, 0], "up": [0, 1, 0], "fov": 45, "resolution": [16, 16]},
  "materials": {"surface": )" + surface + R"(, "ball": )" + ball + R"(,
                "black": {"type": "lambertian", "reflectance": 0}},
  "shapes": [
    {"name": "floor", "type": "rectangle", "center": [0, 0, 0], "u": [0, 0, 4], "v": [4, 0, 0], "material": "surface"},
    {"name": "ball", "type": "sphere", "center": [0.6, 0.4, 0.3], "radius": 0.4, "material": "ball"},
    {"name": "lamp", "type": "rectangle", "center": [0, 1.5, 1.2], "u": [1, 0, 0], "v": [0, 0, 1],
     "material": "black", "emission": {"radiance": "D65", "scale": 4}}
  ]
})";
}

const std::string kZhdanov = R"({"type": "zhdanov", "gloss": 0.5, "gloss_exponent": 20,
  "passive": {"type": "tabulated", "wavelengths": [480, 520], "values": [0, 0.5]},
  "excitation": 0, "emission": {"type": "gaussian", "center": 560, "fwhm": 60}})";
const std::string kWhite = R"({"type": "lambertian", "reflectance": 0.6})";

struct Case {
  const char* name;
  std::string surface, ball;
};

std::vector<test::BatchStats> quadrants(const Scene& scene, int hero, int spp) {
  RenderSettings s = scene.render;
  s.heroWavelengths = hero;
  const std::unique_ptr<Integrator> integrator = makeIntegrator("pt", scene, s);
  return test::regionBatches(
      scene, *integrator, kRes, kRes, 4, [](int x, int y) { return (2 * y / kRes) * 2 + 2 * x / kRes; }, spp, kBatches,
      hero == 1 ? 7919 : 104729);
}

void PrintTo(const Case& c, std::ostream* os) { *os << c.name; }

class HeroAgreement : public ::testing::TestWithParam<Case> {};

TEST_P(HeroAgreement, HeroFourAgreesWithSingleWavelengthPt) {
  const Case& c = GetParam();
  const auto scene = loadSceneFromString(sceneWith(c.surface, c.ball), std::string(c.name) + ".json");
  const std::vector<test::BatchStats> one = quadrants(*scene, 1, 512), hero = quadrants(*scene, 4, 256);
  test::expectRegionsAgree(one, hero, 4.0, 0.0, 0.02);
}

INSTANTIATE_TEST_SUITE_P(
    WavelengthDependentSampling, HeroAgreement,
    ::testing::Values(
        Case{"zhdanov", kZhdanov, kWhite},
        Case{"coated", R"({"type": "coated_fluorescent", "absorption": 0.5, "emission": {"type": "gaussian",
              "center": 520, "fwhm": 40}, "reflectance": {"type": "tabulated", "wavelengths": [400, 700],
              "values": [0.9, 0.1]}, "c": 0, "Q": 0.9, "coat_ior": "BK7", "coat_alpha": 0.1})", kWhite},
        Case{"rough_glass", kWhite, R"({"type": "rough_dielectric", "ior": {"type": "cauchy", "A": 1.5, "B": 0.02,
              "C": 0}, "alpha": 0.2})"}),
    [](const ::testing::TestParamInfo<Case>& info) { return std::string(info.param.name); });

}  // namespace
}  // namespace kasha
