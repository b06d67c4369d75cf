// BDPT in scenes with media (docs/media.md §5):
//   - a light path's free flight knows the density with which a camera path would have drawn the
//     same segment (the source-seeking mixture of eq. 6b, which light paths do not draw from): its
//     recorded optical depths give the mixture's density in closed form, at the collision and past
//     the medium. This was a bias: light paths recorded no seeking depth, and bdpt's own family
//     rendered the fluorescent equilibrium furnace 3% dark, 5σ;
//   - what the bidirectional engine cannot weigh yet is refused in one line: mollification; bpm
//     refuses media (its merges alone cannot reach collisions near a surface). Wavelength lanes
//     (they end at a flight through a medium) and heterogeneous media are accepted.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>

#include <nlohmann/json.hpp>

#include "integrators/integrator_factory.h"
#include "integrators/medium_transport.h"
#include "scene/scene_loader.h"
#include "tests/temp_dir.h"
#include "tests/volume_grid_files.h"

namespace kasha {
namespace {

using nlohmann::json;

// An index-matched fluorescent sphere of radius 1 around the origin, seen along +z from z = −5.
json inkScene() {
  return json::parse(R"({
    "camera": {"position": [0, 0, -5], "look_at": [0, 0, 0], "fov": 30, "resolution": [4, 4]},
    "media": {"ink": {"type": "homogeneous", "sigma_a": 0.05, "sigma_s": 0.3,
              "fluorophores": [{"sigma_f": {"type": "gaussian", "center": 450, "fwhm": 40, "peak": 2},
                                "emission": {"type": "gaussian", "center": 600, "fwhm": 40}, "yield": 0.8}]}},
    "materials": {"white": {"type": "lambertian", "reflectance": 0.5}},
    "shapes": [{"type": "sphere", "center": [0, 0, 0], "radius": 1, "interior": "ink"}],
    "lights": [{"type": "point", "position": [0, 3, 0], "intensity": 1}]
  })");
}

TEST(BidirectionalMedia, LightPathFlightsKnowTheCameraPathsDensity) {
  const auto scene = loadSceneFromJson(inkScene(), "ink.json");
  RayCounter counter;
  int collisions = 0, passes = 0;
  for (const float lambda : {450.0f, 520.0f, 600.0f}) {
    const double sigma = scene->media[0]->sigmaT(lambda);
    const double seek = sigma + scene->mediumScattering[0]->fluorescentWeight(TransportMode::Radiance, lambda);
    if (lambda == 600.0f) {
      ASSERT_GT(seek, 2.0 * sigma);  // at the emission peak the mixture differs
    }
    for (int i = 0; i < 64; ++i) {
      const float u = (float(i) + 0.5f) / 64.0f;
      const FreeFlight f = traceFreeFlight(*scene, Ray{Vec3(0, 0, -5), Vec3(0, 0, 1)}, -1, {&lambda, 1}, u,
                                           TransportMode::Importance, counter);
      // The camera mixture's density of this end: ½(σ·e^{−σt} + σ'·e^{−σ't}) at a collision t into
      // the sphere, ½(e^{−2σ} + e^{−2σ'}) past it (σ' = σ + A_fl, the chord is 2 long).
      const double t = f.collided ? double(f.p.z) + 1.0 : 2.0;
      const double rate = f.collided ? sigma : 1.0, seekRate = f.collided ? seek : 1.0;
      const double exact = 0.5 * (rate * std::exp(-sigma * t) + seekRate * std::exp(-seek * t));
      const double recorded = freeFlightDensity(true, f.depth, float(rate), float(seekRate));
      EXPECT_NEAR(recorded, exact, 1e-4 * exact) << lambda << " nm, u " << u;
      (f.collided ? collisions : passes)++;
    }
  }
  EXPECT_GT(collisions, 10);  // both ends were checked
  EXPECT_GT(passes, 10);
}

class BidirectionalMediaRefusals : public test::TempDirTest {
 protected:
  BidirectionalMediaRefusals() : TempDirTest("bidirectional_media") {}

  // The message of the error making `integrator` for the scene with `settings` changed.
  std::string refusal(const json& scene, const std::string& integrator,
                      const std::function<void(RenderSettings&)>& change = {}) const {
    const auto s = loadSceneFromJson(scene, dir + "/scene.json");
    RenderSettings settings = s->render;
    if (change) change(settings);
    try {
      makeIntegrator(integrator, *s, settings);
    } catch (const std::exception& e) {
      return e.what();
    }
    return "(accepted)";
  }
};

TEST_F(BidirectionalMediaRefusals, WhatItCannotWeighYet) {
  const json ink = inkScene();
  EXPECT_EQ(refusal(ink, "bdpt"), "(accepted)");
  EXPECT_EQ(refusal(ink, "bdpt", [](RenderSettings& s) { s.heroWavelengths = 1; }), "(accepted)");
  EXPECT_EQ(refusal(ink, "bdpt", [](RenderSettings& s) { s.heroWavelengths = 4; }), "(accepted)");
  EXPECT_EQ(refusal(ink, "bdpt",
                    [](RenderSettings& s) {
                      s.bdpt.families = BdptFamilies::Own;
                      s.bdpt.mollify = true;
                    }),
            "bdpt: render/bdpt/mollify: not supported in scenes with media");
  EXPECT_EQ(refusal(ink, "vcm"), "(accepted)");
  EXPECT_EQ(refusal(ink, "vc"), "(accepted)");
  EXPECT_EQ(refusal(ink, "vcm", [](RenderSettings& s) { s.heroWavelengths = 2; }), "(accepted)");
  EXPECT_EQ(refusal(ink, "bpm"), "bpm does not transport participating media (merges alone cannot reach collisions "
                                 "near a surface; vcm and vc do)");
  EXPECT_EQ(refusal(ink, "ppm"), "(accepted)");  // volume photons (docs/photon-mapping.md §9)

  writeFile("smoke.vol", test::volBytes({2, 2, 2}, 1, {0.1f, 0.5f, 1, 0.2f, 0.3f, 0.9f, 0.4f, 0.6f}));
  json smoke = ink;
  smoke["media"]["ink"] = {{"type", "heterogeneous"}, {"sigma_a", 0.1}, {"sigma_s", 0.5}, {"density", {{"file", "smoke.vol"}}}};
  EXPECT_EQ(refusal(smoke, "bdpt"), "(accepted)");  // heterogeneous media: test_heterogeneous_media.cpp
  EXPECT_EQ(refusal(smoke, "vcm"), "(accepted)");
}

}  // namespace
}  // namespace kasha
