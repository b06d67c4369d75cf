// The textured spot light (core/light.h, core/projected_image.h): Mitsuba's direction → (u, v)
// mapping at hand-computed directions, its emission directions' density (the one sampleEmission
// reports and emissionPdfs answers) integrating to 1 over the sphere, and the sampled Le/pdf
// averaging to the intensity's integral over the cone, computed by quadrature: so every direction
// that emits can be sampled, with the density the integrators are told.
#include <gtest/gtest.h>

#include <cmath>

#include "core/light.h"
#include "core/rng.h"
#include "tests/support.h"

namespace kasha {
namespace {

constexpr float kCone = 25.0f, kBeam = 10.0f;

// A 5×3 image with structure: a gradient, a black texel and a bright one (cast onto the cone's
// square, whatever the aspect ratio, as in Mitsuba).
RgbImage texture() {
  RgbImage img{5, 3, {}};
  for (int y = 0; y < 3; ++y)
    for (int x = 0; x < 5; ++x)
      img.pixels.push_back(x == 3 && y == 1 ? Vec3(4.0f, 3.0f, 1.0f) : x == 1 && y == 2 ? Vec3(0.0f)
                                                                        : Vec3(0.1f + 0.2f * float(x), 0.4f, 0.2f * float(y)));
  return img;
}

// At (0, 0, 0) looking along −y, up +z (Mitsuba's look-at: left = up × forward = (+1, 0, 0)).
SpotLight spot() {
  const RgbImage img = texture();
  return SpotLight(Vec3(0.0f), Vec3(0, -1, 0), kCone, kBeam, Spectrum::constant(2.0f), 1.5f, &img, Vec3(0, 0, 1));
}

TEST(SpotTexture, MitsubasMapping) {
  const SpotLight l = spot();
  const float t = std::tan(kCone * kPi / 180.0f);
  // Local (left, up, forward) = (x, z, −y) of the world; u = ½ + ½·x_l/(z_l·tan θc), v likewise.
  for (const Vec3 w : {Vec3(0.1f, -1.0f, 0.2f), Vec3(-0.3f, -1.0f, 0.05f), Vec3(0.0f, -1.0f, -0.4f)}) {
    const std::optional<Vec2> uv = l.directionToUv(glm::normalize(w));
    ASSERT_TRUE(uv.has_value());
    EXPECT_NEAR(uv->x, 0.5f + 0.5f * w.x / (-w.y * t), 1e-5f);
    EXPECT_NEAR(uv->y, 0.5f + 0.5f * w.z / (-w.y * t), 1e-5f);
  }
  EXPECT_FALSE(l.directionToUv(Vec3(0, 1, 0)).has_value());  // behind the light
  // The black texel (column 1, row 2) is dark; its neighbour (column 2) is not.
  const auto towards = [&](float u, float v) {
    return glm::normalize(Vec3((2.0f * u - 1.0f) * t, -1.0f, (2.0f * v - 1.0f) * t));
  };
  EXPECT_EQ(l.emittedTowards(550.0f, Vec3(0.0f), towards(0.3f, 0.75f)), 0.0f);
  EXPECT_GT(l.emittedTowards(550.0f, Vec3(0.0f), towards(0.5f, 0.75f)), 0.0f);
}

// Midpoint quadrature of f(ω) over the directions within `degrees` of the axis, in (cos θ, φ).
template <class F>
double overCone(double degrees, const F& f) {
  constexpr int kN = 1500;
  const double cosMax = std::cos(degrees * M_PI / 180.0), dz = (1.0 - cosMax) / kN, dphi = 2.0 * M_PI / kN;
  double sum = 0.0;
  for (int i = 0; i < kN; ++i) {
    const double z = cosMax + (i + 0.5) * dz, r = std::sqrt(1.0 - z * z);
    for (int j = 0; j < kN; ++j) {
      const double phi = (j + 0.5) * dphi;
      sum += f(Vec3(float(r * std::cos(phi)), float(-z), float(r * std::sin(phi))));
    }
  }
  return sum * dz * dphi;
}

TEST(SpotTexture, DensityIntegratesToOne) {
  const SpotLight l = spot();
  // Over the image's square, out to its corners (√2·tan 25° = tan 33.4°): texels across the cone's
  // edge are sampled beyond it too (sampleEmission then returns nothing).
  const double total = overCone(35.0, [&](const Vec3& w) {
    float pdfPos, pdfDir;
    l.emissionPdfs(Vec3(0.0f), Vec3(0.0f), w, pdfPos, pdfDir);
    return double(pdfDir);
  });
  // The texels' edges cut the quadrature's cells: 0.2% of error.
  EXPECT_NEAR(total, 1.0, 2e-3);
}

TEST(SpotTexture, SampledIntensityIntegratesOverTheCone) {
  const SpotLight l = spot();
  const float lambda = 600.0f;
  const double exact = overCone(kCone, [&](const Vec3& w) { return double(l.emittedTowards(lambda, Vec3(0.0f), w)); });
  Rng rng(7);
  constexpr int kSamples = 200000;
  double sum = 0.0, sum2 = 0.0;
  for (int i = 0; i < kSamples; ++i) {
    const std::optional<EmissionSample> s = l.sampleEmission(lambda, Vec2(0.5f), Vec2{rng.uniform(), rng.uniform()});
    double x = 0.0;
    if (s) {
      float pdfPos, pdfDir;
      l.emissionPdfs(s->p, s->n, s->w, pdfPos, pdfDir);
      EXPECT_NEAR(pdfDir, s->pdfDir, 1e-4f * s->pdfDir);  // the density reported is the one answered
      EXPECT_FLOAT_EQ(l.emitted(*s, lambda), s->Le);
      x = double(s->Le) / double(s->pdfDir);
    }
    sum += x;
    sum2 += x * x;
  }
  const double mean = sum / kSamples, stderr_ = std::sqrt((sum2 / kSamples - mean * mean) / kSamples);
  EXPECT_NEAR(mean, exact, 4.0 * stderr_ + 2e-3 * exact);
  EXPECT_LT(stderr_, 0.01 * exact) << "too noisy to test";
}

}  // namespace
}  // namespace kasha
