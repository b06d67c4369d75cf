// Rays across index-matched boundaries (integrators/medium_transport.h) against the exact optical
// depth of a slab: a ray entering it at cosine μ to its normal travels d/μ in it. Both functions
// go on from a point offsetPoint moves ε off the boundary; the ε/μ of medium behind that point
// must still count (validation.md §5a: a slab 0.01 thick lost 0.3% of its fluorescence when it
// did not). Deterministic: the slab's optical depth, about 1, is checked to 10⁻⁵, where the
// skipped layer (ε ≥ 2·10⁻⁵ over d = 0.1) would be 2·10⁻⁴.
#include <gtest/gtest.h>

#include <cmath>

#include "integrators/medium_transport.h"
#include "scene/scene_loader.h"
#include "tests/support.h"

namespace kasha {
namespace {

constexpr float kThickness = 0.1f;
const float kLambda[2] = {450.0f, 600.0f};

// An index-matched slab y in [−0.1, 0], 2 wide, whose σ_t is 5 at 450 nm and 8 at 600 nm.
std::unique_ptr<Scene> slabScene() {
  const std::string text = R"({
    "camera": {"position": [0, 3, 0], "look_at": [0, 0, 0], "up": [0, 0, 1], "fov": 30, "resolution": [4, 4]},
    "media": {"m": {"type": "homogeneous",
                    "sigma_a": {"type": "tabulated", "wavelengths": [450, 600], "values": [3, 8]},
                    "sigma_s": {"type": "tabulated", "wavelengths": [450, 600], "values": [2, 0]}}},
    "materials": {"unused": {"type": "lambertian", "reflectance": 0}},
    "shapes": [{"type": "mesh", "file": "unit_cube.obj", "interior": "m",
                "transform": [[2, 0, 0, 0], [0, 0.1, 0, -0.05], [0, 0, 2, 0], [0, 0, 0, 1]]}],
    "lights": [{"type": "distant", "direction": [0, -1, 0], "irradiance": 1}]})";
  return loadSceneFromString(text, test::sourcePath("scenes/validation/slab_test.json"));
}

// A unit direction going down at cosine μ to the slab's normal.
Vec3 downAt(float mu) { return Vec3(std::sqrt(1.0f - mu * mu), -mu, 0.0f); }

TEST(BoundaryCrossing, TransmittanceAcrossASlabIsExpOfSigmaDOverMu) {
  const auto scene = slabScene();
  RayCounter counter;
  for (const float mu : {1.0f, 0.6f, 0.3f}) {
    SCOPED_TRACE("mu " + std::to_string(mu));
    const Vec3 d = downAt(mu);
    const Vec3 origin = -d * (0.5f / mu);  // 0.5 above the entry point (0, 0, 0)
    float tr[2];
    // Through the slab to a point 0.5 below it.
    ASSERT_TRUE(segmentTransmittance(*scene, origin, d, (1.0f + kThickness) / mu, -1, kLambda, tr, counter));
    EXPECT_NEAR(-std::log(tr[0]), 5.0 * kThickness / mu, 1e-5 * 5.0 * kThickness / mu);
    EXPECT_NEAR(-std::log(tr[1]), 8.0 * kThickness / mu, 1e-5 * 8.0 * kThickness / mu);
    // To a point inside it, at depth 0.06.
    ASSERT_TRUE(segmentTransmittance(*scene, origin, d, (0.5f + 0.06f) / mu, -1, kLambda, tr, counter));
    EXPECT_NEAR(-std::log(tr[0]), 5.0 * 0.06 / mu, 1e-5 * 5.0 * 0.06 / mu);
  }
}

TEST(BoundaryCrossing, FreeFlightCollidesExactlyWithinTheSlabsOpticalDepth) {
  const auto scene = slabScene();
  RayCounter counter;
  for (const float mu : {1.0f, 0.6f}) {
    SCOPED_TRACE("mu " + std::to_string(mu));
    const Vec3 d = downAt(mu);
    const Ray ray{-d * (0.5f / mu), d};
    const double tau = 5.0 * kThickness / mu;  // the slab's optical depth at lane 0
    // Optical depth τ(1 − 5·10⁻⁵) ends the flight inside, 5·10⁻⁶ above the far face.
    const float inside = float(-std::expm1(-tau * (1.0 - 5e-5)));
    const FreeFlight collided = traceFreeFlight(*scene, ray, -1, kLambda, inside, TransportMode::Importance, counter);
    ASSERT_TRUE(collided.collided);
    EXPECT_NEAR(collided.p.y, -kThickness * (1.0 - 5e-5), 1e-6);
    // Lane 1's weight T_1/p_0 = e^{τ_0 − τ_1}/σ_0 at the same point (σ_t 8 and 5).
    EXPECT_NEAR(collided.weight[1], std::exp(-3.0 * kThickness * (1.0 - 5e-5) / mu) / 5.0, 1e-5);
    // τ(1 + 5·10⁻⁵) passes through: weight e^{τ_0 − τ_1} for lane 1.
    const float beyond = float(-std::expm1(-tau * (1.0 + 5e-5)));
    const FreeFlight passed = traceFreeFlight(*scene, ray, -1, kLambda, beyond, TransportMode::Importance, counter);
    EXPECT_FALSE(passed.collided);
    EXPECT_FALSE(passed.hit.has_value());
    EXPECT_EQ(passed.medium, -1);
    EXPECT_NEAR(passed.weight[1], std::exp(-3.0 * kThickness / mu), 1e-5);
  }
}

}  // namespace
}  // namespace kasha
