// The projector light (core/projector_light.h): a white projector of irradiance E = (1, 1, 1) (D65
// with Y = 1, core/rgb_illuminant.h) at distance d on the axis of a Lambertian plane of reflectance
// ρ facing it: at angle θ off the axis the plane is d/cos θ away and lit at incidence cos θ, so its
// irradiance is I(θ)·cos³θ/d² = π·scale·E/d² everywhere in the beam, its radiance ρ·scale·E/d²,
// and its Y ρ·scale/d². The camera sees a patch inside the beam. Every integrator, within 4σ of that; and a one-texel image lights
// only the quarter of the plane that its corner of the image maps to (Mitsuba's orientation: image
// left is the projector's left, row 0 its top).
#include <gtest/gtest.h>

#include <fstream>
#include <string>

#include <stb/stb_image_write.h>

#include "integrators/integrator_factory.h"
#include "integrators/render_loop.h"
#include "scene/scene_loader.h"
#include "tests/integrator_names.h"
#include "tests/region_batches.h"
#include "tests/support.h"
#include "tests/temp_dir.h"

namespace kasha {
namespace {

constexpr float kRho = 0.5f, kScale = 1.5f, kDistance = 2.0f;

std::string scene(const std::string& light, float fov) {
  return R"({"render": {"spp": 1, "max_depth": 1, "sensor_sampling": "cmf"},
    "camera": {"position": [0, 0, 3], "look_at": [0, 0, 0], "fov": )" + std::to_string(fov) + R"(, "resolution": [8, 8]},
    "materials": {"white": {"type": "lambertian", "reflectance": )" + std::to_string(kRho) + R"(}},
    "shapes": [{"type": "rectangle", "center": [0, 0, 0], "u": [3, 0, 0], "v": [0, 3, 0], "material": "white"}],
    "lights": [)" + light + "]}";
}

TEST(Projector, IrradianceOnItsAxisInEveryIntegrator) {
  // Slightly off the camera's axis, so that the camera does not look through the projector's point;
  // its beam (±0.54 at the plane) holds what the camera sees (±0.32).
  const auto s = loadSceneFromString(
      scene(R"({"type": "projector", "position": [0.01, 0, 2], "look_at": [0.01, 0, 0], "fov": 30,
                "irradiance": [1, 1, 1], "scale": )" + std::to_string(kScale) + "}", 12.0f),
      "projector.json");
  test::setPhotons(*s, 500, 0.05f);
  const double expected = double(kRho) * kScale / (kDistance * kDistance) * 64.0;  // summed over 8×8 pixels
  for (const std::string& name : {"pt", "lt", "bdpt", "vcm"}) {
    SCOPED_TRACE(name);
    const auto integrator = test::makeTestIntegrator(name, *s, s->render);
    const auto stats = test::regionBatches(*s, *integrator, 8, 8, 1, [](int, int) { return 0; }, 8, 8, 11);
    const test::BatchStats& y = stats[1];
    // 1% of the value bounds the D65 upsampling's table tolerance, besides the estimator's 4σ.
    EXPECT_NEAR(y.mean, expected, 4.0 * y.stderr_ + 0.01 * expected);
    EXPECT_LT(y.stderr_, 0.02 * expected) << "too noisy to test";
  }
}

class ProjectorImage : public test::TempDirTest {
 protected:
  ProjectorImage() : TempDirTest("projector_image") {}
};

TEST_F(ProjectorImage, AnImageCornerLightsItsQuadrant) {
  // A 2×2 image whose top-left texel alone is lit. The projector at +z looks down −z with up +y, so
  // its left (Mitsuba's look-at: x = up × forward) is the scene's −x, its top +y.
  const unsigned char px[12] = {255, 255, 255, 0, 0, 0, 0, 0, 0, 0, 0, 0};
  const std::string image = dir + "/corner.png";
  ASSERT_TRUE(stbi_write_png(image.c_str(), 2, 2, 3, px, 6));
  const auto s = loadSceneFromString(
      scene(R"({"type": "projector", "position": [0, 0, 2], "look_at": [0, 0, 0], "fov": 60, "image": ")" + image + R"("})",
            60.0f),
      dir + "/scene.json");
  const auto integrator = test::makeTestIntegrator("pt", *s, s->render);
  Film film(8, 8);
  RenderOptions opt;
  opt.spp = 4;
  render(*s, *integrator, film, opt);
  // The camera also looks down −z with up +y: the lit quadrant (−x, +y) is its image's top left.
  double lit = 0.0, dark = 0.0;
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 8; ++x) (x < 4 && y < 4 ? lit : dark) += film.xyz(x, y).y;
  EXPECT_GT(lit, 0.0);
  EXPECT_EQ(dark, 0.0);
}

}  // namespace
}  // namespace kasha
