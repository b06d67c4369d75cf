// Lights that cast an image (core/projected_image.h). The projector (core/projector_light.h): a white projector of irradiance E = (1, 1, 1) (D65
// with Y = 1, core/rgb_illuminant.h) at distance d on the axis of a Lambertian plane of reflectance
// ρ facing it: at angle θ off the axis the plane is d/cos θ away and lit at incidence cos θ, so its
// irradiance is I(θ)·cos³θ/d² = π·scale·E/d² everywhere in the beam, its radiance ρ·scale·E/d²,
// and its Y ρ·scale/d². The camera sees a patch inside the beam. Every integrator, within 4σ of that; and a one-texel image lights
// only the quarter of the plane that its corner of the image maps to (Mitsuba's orientation: image
// left is the projector's left, row 0 its top).
// The textured spot (core/light.h): a grey texture cast over the cone at distance d above the plane.
// The plane's irradiance is I(ω)·cos³θ/d², so its radiance integrated over a rectangle the camera sees
// is ρ/π·scale·T·Ω, Ω the rectangle's solid angle from the spot; the camera's pixels have equal
// footprints on the plane, so a quarter of the image, lit by one texel, sums to that over a
// footprint's area, in every integrator. And a one-texel
// texture lights the quarter Mitsuba's mapping sends it to (the image turned by 180° seen from the
// light).
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <fstream>
#include <string>
#include <vector>

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

// Solid angle of the rectangle [0, w] × [0, h] seen from height d above its corner, ∫ d/(d² + r²)^{3/2} dA.
double cornerRectangleSolidAngle(double w, double h, double d) { return std::atan(w * h / (d * std::sqrt(d * d + w * w + h * h))); }

// A w×h PNG of grey bytes (R = G = B), row 0 at the top.
std::string writeGreyPng(const std::string& path, int w, int h, const std::vector<unsigned char>& grey) {
  std::vector<unsigned char> rgb;
  for (unsigned char g : grey) rgb.insert(rgb.end(), {g, g, g});
  EXPECT_TRUE(stbi_write_png(path.c_str(), w, h, 3, rgb.data(), 3 * w));
  return path;
}

// The camera's quarter of pixel (x, y) of the 8×8 image: (x ≥ 4) + 2·(y ≥ 4), row 0 at the top.
int quarterOf(int x, int y) { return (x >= 4 ? 1 : 0) + (y >= 4 ? 2 : 0); }

// Y summed over each quarter of a small pt render of the scene.
std::array<double, 4> quarterSums(const Scene& s) {
  const auto integrator = test::makeTestIntegrator("pt", s, s.render);
  Film film(8, 8);
  RenderOptions opt;
  opt.spp = 4;
  render(s, *integrator, film, opt);
  std::array<double, 4> y{};
  for (int py = 0; py < 8; ++py)
    for (int px = 0; px < 8; ++px) y[size_t(quarterOf(px, py))] += film.xyz(px, py).y;
  return y;
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
  const std::string image = writeGreyPng(dir + "/corner.png", 2, 2, {255, 0, 0, 0});
  const auto s = loadSceneFromString(
      scene(R"({"type": "projector", "position": [0, 0, 2], "look_at": [0, 0, 0], "fov": 60, "image": ")" + image + R"("})",
            60.0f),
      dir + "/scene.json");
  // The camera also looks down −z with up +y: the lit quadrant (−x, +y) is its image's top left.
  const std::array<double, 4> y = quarterSums(*s);
  EXPECT_GT(y[0], 0.0);
  EXPECT_EQ(y[1] + y[2] + y[3], 0.0);
}

TEST_F(ProjectorImage, TexturedSpotIrradianceInEveryIntegrator) {
  // A 4×4 texture, cone 20° with the falloff from 14°: the camera's view (±0.32 at the plane, up to
  // 0.158 = tan 9° off the spot's axis along x or y) lies in the four central texels (up to
  // ½·tan 20° = 0.182), at full intensity; the rim, its corners in the falloff, is sampled too
  // but lights the plane outside the view.
  constexpr unsigned char tl = 200, tr = 100, bl = 50, br = 150, rim = 40;
  const std::string texture = writeGreyPng(dir + "/spot.png", 4, 4,
                                           {rim, rim, rim, rim, rim, tl, tr, rim, rim, bl, br, rim, rim, rim, rim, rim});
  const auto s = loadSceneFromString(
      scene(R"({"type": "spot", "position": [0, 0, 2], "look_at": [0, 0, 0], "up": [0, 1, 0],
                "cone_angle": 20, "falloff_start": 14, "intensity": 1, "texture": ")" + texture +
                R"(", "encoding": "linear", "scale": )" + std::to_string(kScale) + "}",
            12.0f),
      dir + "/scene.json");
  test::setPhotons(*s, 500, 0.05f);
  // Mitsuba's mapping (src/emitters/spot.cpp): u = ½ + ½·x/(z·tan θc), v likewise in y, with the
  // look-at frame's x = up × forward = −x of the scene and y = +y here; row 0 at v = 0. So the
  // texel above-left of the centre (u, v < ½) lights x > 0, y < 0: the camera's (looking down −z,
  // up +y, row 0 at the top) bottom-right quarter, region 3 below.
  const unsigned char texelOf[4] = {br, bl, tr, tl};  // regions (−x, +y), (+x, +y), (−x, −y), (+x, −y)
  const double a = 3.0 * std::tan(6.0 * M_PI / 180.0);  // the view's half-width on the plane
  const double footprint = (2.0 * a / 8.0) * (2.0 * a / 8.0);
  const double quarterSum = double(kRho) / M_PI * kScale * cornerRectangleSolidAngle(a, a, kDistance) / footprint;
  for (const std::string& name : {"pt", "lt", "bdpt", "vcm"}) {
    SCOPED_TRACE(name);
    const auto integrator = test::makeTestIntegrator(name, *s, s->render);
    const auto stats = test::regionBatches(*s, *integrator, 8, 8, 4, quarterOf, 16, 8, 13);
    for (int r = 0; r < 4; ++r) {
      SCOPED_TRACE("region " + std::to_string(r));
      const test::BatchStats& y = stats[size_t(r) * 3 + 1];
      const double expected = texelOf[r] / 255.0 * quarterSum;
      // 1% bounds the grey texels' upsampling (the coefficient table's tolerance), besides 4σ.
      EXPECT_NEAR(y.mean, expected, 4.0 * y.stderr_ + 0.01 * expected);
      EXPECT_LT(y.stderr_, 0.03 * expected) << "too noisy to test";
    }
  }
}

TEST_F(ProjectorImage, ASpotTexturesTexelLandsWhereMitsubaPutsIt) {
  // A 2×2 texture whose top-left texel alone is lit, cast by a spot at +z looking down −z with up
  // +y: its look-at x (left) is the scene's −x, so u < ½ (the image's left column) is the scene's
  // +x, and v < ½ (row 0) its −y. The camera, looking down −z with up +y, sees that quarter at
  // its image's bottom right.
  const std::string texture = writeGreyPng(dir + "/corner.png", 2, 2, {255, 0, 0, 0});
  const auto s = loadSceneFromString(
      scene(R"({"type": "spot", "position": [0, 0, 2], "look_at": [0, 0, 0], "cone_angle": 30, "intensity": 1,
                "texture": ")" + texture + R"("})", 60.0f),
      dir + "/scene.json");
  const std::array<double, 4> y = quarterSums(*s);
  EXPECT_GT(y[3], 0.0);
  EXPECT_EQ(y[0] + y[1] + y[2], 0.0);
}

}  // namespace
}  // namespace kasha
