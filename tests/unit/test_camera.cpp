// The cameras (core/camera.h): pinhole, thin lens and orthographic.
// - A point on a camera ray, connected through the same lens sample, lands where the ray's film
//   position was, at the ray's origin, and the connection's ray density is generateRay's, measured
//   here from the rays themselves (the solid angle, or for parallel rays the area, that a small
//   patch of film covers).
// - The thin lens is sharp on its plane of focus: a point there lands on one film position through
//   every lens point.
// - The importance is normalised: a surface of radiance 1 covering the view, integrated over its
//   area (and the lens) with the connection's importance·|cosθ|, gives 1 in every pixel.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "core/camera.h"
#include "core/rng.h"

namespace kasha {
namespace {

const int kW = 320, kH = 200;

struct Named {
  const char* name;
  Camera camera;
};

std::vector<Named> cameras() {
  const Vec3 pos(1, 2, -5), at(0.5f, 1.5f, 0), up(0, 1, 0);
  return {{"pinhole", Camera(pos, at, up, 50.0f, kW, kH)},
          {"thin lens", Camera::thinLens(pos, at, up, 50.0f, kW, kH, 0.3f, 4.0f)},
          {"orthographic", Camera::orthographic(pos, at, up, Vec2(3.2f, 2.0f), kW, kH)}};
}

TEST(Camera, ConnectionInvertsTheRayAndCarriesItsDensity) {
  for (const auto& [name, camera] : cameras()) {
    Rng rng(7);
    for (int i = 0; i < 500; ++i) {
      const Vec2 film(2.0f + rng.uniform() * float(kW - 4), 2.0f + rng.uniform() * float(kH - 4));
      const Vec2 lens(rng.uniform(), rng.uniform());
      const Ray ray = camera.generateRay(film, lens);
      const Vec3 p = ray.o + ray.d * (0.5f + 20.0f * rng.uniform());
      const std::optional<Camera::Connection> c = camera.connect(p, lens);
      ASSERT_TRUE(c) << name << " " << i;
      EXPECT_NEAR(c->pixel.x, film.x, 2e-3f) << name << " " << i;
      EXPECT_NEAR(c->pixel.y, film.y, 2e-3f) << name << " " << i;
      EXPECT_NEAR(glm::length(c->lensPoint - ray.o), 0.0f, 1e-4f) << name << " " << i;
      EXPECT_NEAR(glm::dot(-c->wi, ray.d), 1.0f, 1e-5f) << name << " " << i;
      EXPECT_NEAR(c->dist, glm::length(p - ray.o), 1e-3f) << name << " " << i;
      // generateRay is uniform over the film (density 1/(w·h) per pixel²): its density is 1/(w·h)
      // over the solid angle (perspective, from one lens point) or the area (orthographic) per
      // pixel², from central differences of the rays.
      const float e = 0.25f;
      const Ray xp = camera.generateRay(film + Vec2(e, 0), lens), xm = camera.generateRay(film - Vec2(e, 0), lens);
      const Ray yp = camera.generateRay(film + Vec2(0, e), lens), ym = camera.generateRay(film - Vec2(0, e), lens);
      const float perPixel2 = camera.parallelRays() ? glm::length(glm::cross(xp.o - xm.o, yp.o - ym.o)) / (4.0f * e * e)
                                                    : glm::length(glm::cross(xp.d - xm.d, yp.d - ym.d)) / (4.0f * e * e);
      const float expected = 1.0f / (float(kW) * float(kH) * perPixel2);
      EXPECT_NEAR(c->pdfRay / expected, 1.0f, 2e-3f) << name << " " << i;
      EXPECT_NEAR(c->pdfRay / camera.rayPdf(ray), 1.0f, 1e-5f) << name << " " << i;
    }
    // Behind the camera's view plane.
    EXPECT_FALSE(camera.connect(Vec3(1, 2, -6), Vec2(0.5f))) << name;
  }
}

// A reconstruction filter's reach widens the film by filmMargin pixels on every side: a ray through
// a film position just outside the image connects back to it, with the ray's density, only when
// the margin holds that position.
TEST(Camera, FilmMarginWidensTheFilmForConnectionsAndDensities) {
  const float margin = 1.5f;
  for (const auto& [name, camera] : cameras()) {
    for (const Vec2 film : {Vec2(-1.0f, 0.5f * kH), Vec2(kW + 1.2f, kH + 0.4f), Vec2(0.5f * kW, -1.4f)}) {
      const Vec2 lens(0.3f, 0.8f);
      const Ray ray = camera.generateRay(film, lens);
      const Vec3 p = ray.o + 7.0f * ray.d;
      const std::optional<Camera::Connection> c = camera.connect(p, lens, margin);
      ASSERT_TRUE(c) << name;
      EXPECT_NEAR(c->pixel.x, film.x, 2e-3f) << name;
      EXPECT_NEAR(c->pixel.y, film.y, 2e-3f) << name;
      EXPECT_NEAR(camera.rayPdf(ray, margin) / c->pdfRay, 1.0f, 1e-5f) << name;
      EXPECT_FALSE(camera.connect(p, lens)) << name;
      EXPECT_EQ(camera.rayPdf(ray), 0.0f) << name;
      const Ray beyond = camera.generateRay(film + 2.0f * (film - Vec2(0.5f * kW, 0.5f * kH)) / float(kW), lens);
      EXPECT_FALSE(camera.connect(beyond.o + 7.0f * beyond.d, lens, margin)) << name;
      EXPECT_EQ(camera.rayPdf(beyond, margin), 0.0f) << name;
    }
  }
}

// At another resolution the camera keeps its projection and its vertical extent: the rays through
// the middle of the top edge and of the film agree.
TEST(Camera, ResizedKeepsTheProjectionAndTheVerticalExtent) {
  for (const auto& [name, camera] : cameras()) {
    const Camera small = camera.resized(40, 50);
    EXPECT_EQ(small.width(), 40);
    EXPECT_EQ(small.parallelRays(), camera.parallelRays());
    EXPECT_EQ(small.apertureRadius(), camera.apertureRadius());
    for (const float v : {0.0f, 0.5f}) {
      const Vec2 lens(0.3f, 0.8f);
      const Ray a = camera.generateRay(Vec2(0.5f * kW, v * kH), lens), b = small.generateRay(Vec2(20.0f, v * 50.0f), lens);
      EXPECT_NEAR(glm::length(a.o - b.o), 0.0f, 1e-5f) << name;
      EXPECT_NEAR(glm::dot(a.d, b.d), 1.0f, 1e-6f) << name;
    }
  }
}

TEST(Camera, ThinLensIsSharpOnItsPlaneOfFocus) {
  const Camera camera = cameras()[1].camera;
  Rng rng(3);
  for (int i = 0; i < 100; ++i) {
    const Vec2 film(rng.uniform() * float(kW), rng.uniform() * float(kH));
    // The point at distance f along the view axis on the pinhole ray through the film position.
    const Ray chief = camera.generateRay(film, Vec2(0.5f));  // the lens centre
    const Vec3 p = chief.o + chief.d * (camera.focusDistance() / glm::dot(chief.d, camera.forward()));
    for (int j = 0; j < 4; ++j) {
      const Vec2 lens(rng.uniform(), rng.uniform());
      const std::optional<Camera::Connection> c = camera.connect(p, lens);
      ASSERT_TRUE(c);
      EXPECT_NEAR(c->pixel.x, film.x, 2e-3f) << i;
      EXPECT_NEAR(c->pixel.y, film.y, 2e-3f) << i;
      // The lens point lies on the lens: in the view plane, within the aperture.
      const Vec3 offset = c->lensPoint - camera.position();
      EXPECT_NEAR(glm::dot(offset, camera.forward()), 0.0f, 1e-5f);
      EXPECT_LE(glm::length(offset), camera.apertureRadius() * (1.0f + 1e-5f));
    }
  }
}

// A rectangle (centre c, edge vectors u, v) beyond the camera, with radiance 1 towards it: Monte
// Carlo over its area and the lens of Σ_j ∫ importance·|cosθ| dA into each pixel of a small film.
// Each pixel measures the mean radiance over its rays, 1: the sum is 1 per pixel.
TEST(Camera, ImportanceIntegratesToOnePerPixel) {
  const int w = 4, h = 3;
  const Vec3 pos(0.2f, 1, -4), at(0, 0.5f, 0), up(0, 1, 0);
  const Vec3 c(0, 0, 2), u(7, 0, 0), v(0, 6, 1.6f);  // tilted, covering the view from any lens point
  const Vec3 n = glm::normalize(glm::cross(u, v));
  const float area = glm::length(glm::cross(u, v));
  for (const Camera& camera : {Camera(pos, at, up, 30.0f, w, h), Camera::thinLens(pos, at, up, 30.0f, w, h, 0.4f, 2.5f),
                               Camera::orthographic(pos, at, up, Vec2(5.0f, 3.75f), w, h)}) {
    const int samples = 1000000;
    std::vector<double> sum(size_t(w * h), 0.0), sum2(size_t(w * h), 0.0);
    Rng rng(11);
    for (int i = 0; i < samples; ++i) {
      const Vec3 p = c + (rng.uniform() - 0.5f) * u + (rng.uniform() - 0.5f) * v;
      const std::optional<Camera::Connection> k = camera.connect(p, Vec2(rng.uniform(), rng.uniform()));
      if (!k) continue;
      const size_t j = size_t(int(k->pixel.y) * w + int(k->pixel.x));
      const double value = double(k->importance) * std::abs(glm::dot(n, k->wi)) * area;
      sum[j] += value;
      sum2[j] += value * value;
    }
    for (size_t j = 0; j < sum.size(); ++j) {
      const double mean = sum[j] / samples;
      const double stderr_ = std::sqrt((sum2[j] / samples - mean * mean) / samples);
      EXPECT_LT(stderr_, 0.01) << camera.parallelRays() << " pixel " << j;
      EXPECT_NEAR(mean, 1.0, 4.0 * stderr_) << "orthographic " << camera.parallelRays() << " lens "
                                            << camera.apertureRadius() << " pixel " << j;
    }
  }
}

}  // namespace
}  // namespace kasha
