// A homogeneous medium's spatially varying albedo (docs/media.md §7; core/grid_albedo.h): the
// grid's colour at world points through its transform and the repeat wrap, worked out by hand, and
// the collision kernel Scene::mediumBsdf builds there, f = α(x, λ)·σ_t(λ)·p_HG, against the
// Henyey–Greenstein formula written out here; a medium without a grid keeps its shared model.
#include <gtest/gtest.h>

#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

#include "core/grid_albedo.h"
#include "materials/bsdf.h"
#include "scene/scene_loader.h"
#include "tests/temp_dir.h"
#include "tests/volume_grid_files.h"

namespace kasha {
namespace {

constexpr uint64_t kLimit = uint64_t(1) << 30;
const Vec3 kRed(0.9f, 0.3f, 0.1f), kBlue(0.1f, 0.4f, 0.8f);

// Two cells along x, red then blue (one along y and z).
std::string twoColours() {
  return test::volBytes({2, 1, 1}, 3, {kRed.x, kRed.y, kRed.z, kBlue.x, kBlue.y, kBlue.z});
}

void expectColour(const Vec3& got, const Vec3& want) {
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(got[c], want[c], 1e-5f) << "channel " << c;
}

TEST(GridAlbedo, ColoursThroughTheTransformAndTheRepeatWrap) {
  // The unit cube scaled by 2 and moved to x = 10: u.x = (p.x − 10)/2; cell centres at u.x = 1/4
  // (red) and 3/4 (blue), i.e. world x = 10.5 and 11.5, repeating every 2 units.
  const glm::mat4 toWorld = glm::scale(glm::translate(glm::mat4(1.0f), Vec3(10, 0, 0)), Vec3(2.0f));
  const GridAlbedo a(VolumeGrid::parse(twoColours(), "albedo.vol", kLimit), toWorld, false, GridWrap::Repeat);
  expectColour(a.colour(Vec3(10.5f, 0.3f, 0.6f)), kRed);
  expectColour(a.colour(Vec3(11.5f, -5.0f, 9.0f)), kBlue);  // y, z beyond the cube: one cell, repeated
  expectColour(a.colour(Vec3(9.5f, 0.5f, 0.5f)), kBlue);    // one period before: u.x = −1/4 ≡ 3/4
  expectColour(a.colour(Vec3(20.5f, 0.5f, 0.5f)), kRed);    // five periods on
  expectColour(a.colour(Vec3(11.0f, 0.5f, 0.5f)), (kRed + kBlue) * 0.5f);  // between the centres
  expectColour(a.colour(Vec3(10.0f, 0.5f, 0.5f)), (kRed + kBlue) * 0.5f);  // between blue (wrapped) and red
  expectColour(a.colour(Vec3(10.25f, 0.5f, 0.5f)), kRed * 0.75f + kBlue * 0.25f);
  // The spectrum is the colour's upsampling.
  const RgbSigmoid s = a.albedo(Vec3(10.5f, 0.0f, 0.0f)), red = rgbToSigmoid(kRed);
  for (float l : {400.0f, 550.0f, 700.0f}) EXPECT_FLOAT_EQ(s(l), red(l));
  // A grey grid: one channel read as R = G = B.
  const GridAlbedo grey(VolumeGrid::parse(test::volBytes({1, 1, 1}, 1, {0.4f}), "grey.vol", kLimit), glm::mat4(1.0f),
                        false, GridWrap::Clamp);
  expectColour(grey.colour(Vec3(3.0f)), Vec3(0.4f));
}

class AlbedoGridScene : public test::TempDirTest {
 protected:
  AlbedoGridScene() : TempDirTest("albedo_grid") {}
  // A sphere of "fog" (σ_t rising from 1 at 400 nm to 3 at 700, g = 0.6, with the albedo grid
  // repeating every unit) beside one of "plain" (no grid).
  std::unique_ptr<Scene> load() {
    writeFile("albedo.vol", twoColours());
    return loadSceneFromString(R"({
      "wavelength_range": [400, 700],
      "camera": {"position": [0, 0, -4], "look_at": [0, 0, 0], "fov": 40, "resolution": [4, 4]},
      "materials": {"white": {"type": "lambertian", "reflectance": 0.5}},
      "media": {"fog": {"type": "homogeneous", "g": 0.6,
                        "sigma_t": {"type": "tabulated", "wavelengths": [400, 700], "values": [1, 3]},
                        "albedo_grid": {"file": "albedo.vol", "wrap_mode": "repeat"}},
                "plain": {"type": "homogeneous", "sigma_a": 0.5, "sigma_s": 0.25}},
      "shapes": [{"type": "sphere", "center": [0, 0, 0], "radius": 1, "interior": "fog"},
                 {"type": "sphere", "center": [3, 0, 0], "radius": 1, "interior": "plain"},
                 {"type": "rectangle", "center": [0, 3, 0], "u": [1, 0, 0], "v": [0, 0, 1], "material": "white",
                  "emission": {"radiance": 1, "two_sided": true}}]
    })", dir + "/scene.json");
  }
};

double hg(double mu, double g) { return (1.0 - g * g) / (4.0 * M_PI * std::pow(1.0 + g * g - 2.0 * g * mu, 1.5)); }

TEST_F(AlbedoGridScene, CollisionKernelIsTheAlbedoThereTimesSigmaT) {
  const auto scene = load();
  ASSERT_TRUE(scene->media[0]->spatiallyVaryingAlbedo());
  ASSERT_FALSE(scene->media[1]->spatiallyVaryingAlbedo());
  const Vec3 wi = glm::normalize(Vec3(0.2f, -0.5f, 0.8f)), wo = glm::normalize(Vec3(-0.6f, 0.1f, 0.3f));
  const double mu = -double(glm::dot(wi, wo));
  // Points where the grid is red, blue (the next period's blue centre) and in between.
  struct At {
    Vec3 x, colour;
  };
  for (const At& at : {At{Vec3(0.25f, 0.1f, -0.2f), kRed}, At{Vec3(-0.25f, 0.4f, 0.3f), kBlue},
                       At{Vec3(0.375f, 0.0f, 0.0f), kRed * 0.75f + kBlue * 0.25f}}) {
    const Bsdf local = scene->mediumBsdf(0, at.x);
    const Bsdf bsdf = local;  // the in-place model travels with a copy
    ASSERT_TRUE(bsdf.has(BsdfFlags::Volume));
    EXPECT_FALSE(bsdf.has(BsdfFlags::Fluorescent));
    const RgbSigmoid albedo = rgbToSigmoid(at.colour);
    for (float l : {420.0f, 550.0f, 680.0f}) {
      const double sigmaT = 1.0 + 2.0 * (l - 400.0) / 300.0;
      const double want = albedo(l) * sigmaT * hg(mu, 0.6);
      for (const TransportMode mode : {TransportMode::Radiance, TransportMode::Importance})
        EXPECT_NEAR(bsdf.eval({mode, SpectralLobe::Elastic, l, l}, wi, wo), want, 1e-5 * want) << l;
      // A sampled event's f/pdf is σ_s there.
      const std::optional<ScatterSample> s = bsdf.sample(TransportMode::Radiance, wo, l, Vec3(0.3f, 0.6f, 0.2f));
      ASSERT_TRUE(s);
      EXPECT_NEAR(s->f / s->pdf, albedo(l) * sigmaT, 1e-4 * sigmaT);
    }
  }
  // Without a grid, the medium's one shared model and its own σ_s.
  const Bsdf plain = scene->mediumBsdf(1, Vec3(3, 0, 0));
  EXPECT_EQ(&plain.model(), scene->mediumScattering[1].get());
  EXPECT_NEAR(plain.eval({TransportMode::Radiance, SpectralLobe::Elastic, 500.0f, 500.0f}, wi, wo), 0.25 * hg(mu, 0.0),
              1e-6);
}

}  // namespace
}  // namespace kasha
