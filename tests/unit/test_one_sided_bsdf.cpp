// The Bsdf of a one-sided material (Bsdf::restrictToFront): every query gives nothing unless both
// directions lie in front of the surface, and in front it answers as the two-sided material's;
// only a top-level material may be one-sided.
#include <gtest/gtest.h>

#include <string>

#include "core/error.h"
#include "scene/scene_loader.h"

namespace kasha {
namespace {

std::unique_ptr<Scene> sheet(const std::string& material) {
  return loadSceneFromString(R"({
  "camera": {"position": [0, 0, 2], "look_at": [0, 0, 0], "up": [0, 1, 0], "fov": 30, "resolution": [4, 4]},
  "materials": {"sheet": )" + material + R"(},
  "shapes": [{"type": "rectangle", "corners": [[-1,-1,0], [1,-1,0], [1,1,0], [-1,1,0]], "material": "sheet"}],
  "lights": [{"type": "point", "position": [0, 0, 1], "intensity": 1}]})",
                             "sheet.json");
}

TEST(OneSidedBsdf, ScattersOnlyInFrontAsTheTwoSidedOne) {
  const auto one = sheet(R"({"type": "rough_conductor", "reflectance": 0.8, "alpha": 0.3, "one_sided": true})");
  const auto two = sheet(R"({"type": "rough_conductor", "reflectance": 0.8, "alpha": 0.3})");
  const float lambda[1] = {550.0f};
  const Hit hit = *one->accel->intersect(Ray{Vec3(0.1f, 0.2f, 2.0f), Vec3(0, 0, -1)});
  const Bsdf b1 = one->bsdf(hit, lambda), b2 = two->bsdf(hit, lambda);
  const TransportMode r = TransportMode::Radiance;
  const SpectralLobe el = SpectralLobe::Elastic;
  // Local directions: the sheet's normal is local +z (its front faces the camera).
  const Vec3 front1 = glm::normalize(Vec3(0.3f, 0.1f, 0.9f)), front2 = glm::normalize(Vec3(-0.2f, 0.2f, 0.8f));
  const Vec3 back1 = Vec3(front1.x, front1.y, -front1.z), back2 = Vec3(front2.x, front2.y, -front2.z);
  ASSERT_GT(b2.eval({r, el, 550, 550}, front1, front2), 0.0f);
  EXPECT_EQ(b1.eval({r, el, 550, 550}, front1, front2), b2.eval({r, el, 550, 550}, front1, front2));
  EXPECT_EQ(b1.directionPdf({r, el, 550, 550}, front2, front1), b2.directionPdf({r, el, 550, 550}, front2, front1));
  EXPECT_EQ(b1.pdf({r, el, 550, 550}, front1, front2).pdf, b2.pdf({r, el, 550, 550}, front1, front2).pdf);
  ASSERT_GT(b2.eval({r, el, 550, 550}, back1, back2), 0.0f);  // the two-sided one reflects behind
  for (const auto& [wi, wo] : {std::pair{back1, back2}, std::pair{front1, back2}, std::pair{back1, front2}}) {
    EXPECT_EQ(b1.eval({r, el, 550, 550}, wi, wo), 0.0f);
    EXPECT_EQ(b1.directionPdf({r, el, 550, 550}, wo, wi), 0.0f);
    EXPECT_EQ(b1.pdf({r, el, 550, 550}, wi, wo).pdf, 0.0f);
  }
  // Sampled from behind: nothing; from the front: the two-sided sample.
  int sampledBehind = 0;
  for (int i = 0; i < 64; ++i) {
    const Vec3 u((float(i) + 0.5f) / 64.0f, float((i * 37) % 64 + 0.5f) / 64.0f, float((i * 11) % 64 + 0.5f) / 64.0f);
    sampledBehind += b1.sample(r, back2, 550, u).has_value();
    sampledBehind += b1.sampleDirection({r, el, 550, 550}, back2, Vec2(u.y, u.z)).has_value();
    const std::optional<ScatterSample> s1 = b1.sample(r, front2, 550, u), s2 = b2.sample(r, front2, 550, u);
    ASSERT_EQ(s1.has_value(), s2.has_value() && s2->w.z > 0.0f);
    if (s1) EXPECT_EQ(s1->f, s2->f);
  }
  EXPECT_EQ(sampledBehind, 0);
}

TEST(OneSidedBsdf, OnlyATopLevelMaterialIsOneSided) {
  try {
    sheet(R"({"type": "mask", "opacity": 0.5, "material": {"type": "lambertian", "reflectance": 0.5, "one_sided": true}})");
    ADD_FAILURE() << "a nested one_sided was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("sheet.json: /materials/sheet/material/one_sided: only a top-level material"),
              std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace kasha
