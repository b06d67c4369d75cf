// The pinhole camera (core/camera.h): a point connected to it lands where the camera's own ray
// through that film position points, and the connection's direction density is generateRay's,
// measured here from the rays themselves (the solid angle a small patch of film sees).
#include <gtest/gtest.h>

#include <cmath>

#include "core/camera.h"
#include "core/rng.h"

namespace kasha {
namespace {

TEST(Camera, ConnectionInvertsTheRayAndCarriesItsDirectionDensity) {
  const int w = 320, h = 200;
  const Camera camera(Vec3(1, 2, -5), Vec3(0.5f, 1.5f, 0), Vec3(0, 1, 0), 50.0f, w, h);
  Rng rng(7);
  for (int i = 0; i < 500; ++i) {
    const Vec2 film(2.0f + rng.uniform() * float(w - 4), 2.0f + rng.uniform() * float(h - 4));
    const Ray ray = camera.generateRay(film);
    const Vec3 p = ray.o + ray.d * (0.5f + 20.0f * rng.uniform());
    const std::optional<Camera::Connection> c = camera.connect(p);
    ASSERT_TRUE(c) << i;
    EXPECT_NEAR(c->pixel.x, film.x, 2e-3f) << i;
    EXPECT_NEAR(c->pixel.y, film.y, 2e-3f) << i;
    EXPECT_NEAR(glm::dot(-c->wi, ray.d), 1.0f, 1e-5f) << i;
    // generateRay is uniform over the film (density 1/(w·h) per pixel²), so its density per
    // steradian is 1/(w·h) over the solid angle per pixel², from central differences of the rays.
    const float e = 0.25f;
    const Vec3 dx = camera.generateRay(film + Vec2(e, 0)).d - camera.generateRay(film - Vec2(e, 0)).d;
    const Vec3 dy = camera.generateRay(film + Vec2(0, e)).d - camera.generateRay(film - Vec2(0, e)).d;
    const float solidAnglePerPixel2 = glm::length(glm::cross(dx, dy)) / (4.0f * e * e);
    const float expected = 1.0f / (float(w) * float(h) * solidAnglePerPixel2);
    EXPECT_NEAR(c->pdfDir / expected, 1.0f, 2e-3f) << i;
    EXPECT_NEAR(c->pdfDir / camera.directionPdf(-c->wi), 1.0f, 1e-5f) << i;
  }
  EXPECT_FALSE(camera.connect(Vec3(1, 2, -6)));  // behind the pinhole
}

}  // namespace
}  // namespace kasha
