// Light::Li(sample, λ) — the radiance of a sample next-event estimation took, at another lane's
// wavelength — equals what sampleLi returns at that wavelength with the same random numbers, and
// Light::emitted(sample, λ) what sampleEmission returns, for every kind of light (area, point,
// spot, distant, constant and spectral environment).
#include <gtest/gtest.h>

#include "core/sampler.h"
#include "scene/scene_loader.h"
#include "tests/support.h"

namespace kasha {
namespace {

class LightLanes : public ::testing::TestWithParam<const char*> {};

TEST_P(LightLanes, LiAtAnotherWavelengthIsSampleLiThere) {
  const auto scene = loadScene(test::sourcePath(GetParam()));
  Sampler rng(SamplerKind::Independent, 3, 0, 0);
  int compared = 0;
  for (const auto& light : scene->lights)
    for (int i = 0; i < 200; ++i) {
      const Vec3 p(rng.uniform() - 0.5f, rng.uniform() * 0.5f + 0.2f, rng.uniform() - 0.5f);
      const Vec2 u = rng.uniform2();
      const float lambda1 = 380.0f + 400.0f * rng.uniform(), lambda2 = 380.0f + 400.0f * rng.uniform();
      const std::optional<LightSample> a = light->sampleLi(p, lambda1, u), b = light->sampleLi(p, lambda2, u);
      ASSERT_EQ(a.has_value(), b.has_value());
      if (!a) continue;
      EXPECT_NEAR(light->Li(*a, lambda2), b->Li, 1e-5f * std::abs(b->Li) + 1e-12f) << GetParam() << ", sample " << i;
      compared += b->Li > 0.0f;
    }
  EXPECT_GT(compared, 50) << GetParam();
}

TEST_P(LightLanes, EmittedAtAnotherWavelengthIsSampleEmissionThere) {
  const auto scene = loadScene(test::sourcePath(GetParam()));
  Sampler rng(SamplerKind::Independent, 5, 0, 0);
  int compared = 0;
  for (const auto& light : scene->lights)
    for (int i = 0; i < 200; ++i) {
      const Vec2 uPos = rng.uniform2(), uDir = rng.uniform2();
      const float lambda1 = 380.0f + 400.0f * rng.uniform(), lambda2 = 380.0f + 400.0f * rng.uniform();
      const std::optional<EmissionSample> a = light->sampleEmission(lambda1, uPos, uDir),
                                          b = light->sampleEmission(lambda2, uPos, uDir);
      ASSERT_EQ(a.has_value(), b.has_value());
      if (!a) continue;
      EXPECT_NEAR(light->emitted(*a, lambda2), b->Le, 1e-5f * std::abs(b->Le) + 1e-12f) << GetParam() << ", sample " << i;
      compared += b->Le > 0.0f;
    }
  EXPECT_GT(compared, 50) << GetParam();
}

INSTANTIATE_TEST_SUITE_P(Scenes, LightLanes,
                         ::testing::Values("scenes/cornell_uv.json",                              // area, spot
                                           "scenes/validation/furnace_point_light.json",          // point
                                           "scenes/validation/smooth_sphere_distant.json",        // distant
                                           "scenes/validation/single_sphere_environment.json",    // environment
                                           "scenes/jung18_fig1.json"),  // environment with a spectrum
                         [](const auto& info) {
                           std::string n = info.param;
                           n = n.substr(n.rfind('/') + 1);
                           for (char& ch : n)
                             if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
                           return n;
                         });

}  // namespace
}  // namespace kasha
