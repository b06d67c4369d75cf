// The beam radiance estimate's query (integrators/points_near_segments.h) against a brute-force
// search over every point: random points in a box, segments long and short (shorter than the radius,
// inside one sphere, of length zero), from inside the cloud and from outside it.
#include <gtest/gtest.h>

#include <random>

#include "integrators/points_near_segments.h"

namespace kasha {
namespace {

// Every point within r of the segment across it, by the distance to its line: the reference.
std::vector<PointsNearSegments::Found> bruteForce(const std::vector<Vec3>& points, float r, const Vec3& o, const Vec3& d,
                                                  float length) {
  std::vector<PointsNearSegments::Found> found;
  for (size_t i = 0; i < points.size(); ++i) {
    const double t = double(points[i].x - o.x) * d.x + double(points[i].y - o.y) * d.y + double(points[i].z - o.z) * d.z;
    if (t < 0.0 || t > length) continue;
    const double ax = points[i].x - o.x - t * d.x, ay = points[i].y - o.y - t * d.y, az = points[i].z - o.z - t * d.z;
    if (ax * ax + ay * ay + az * az < double(r) * r) found.push_back({uint32_t(i), float(t)});
  }
  return found;
}

TEST(PointsNearSegments, FindWhatABruteForceSearchFinds) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  std::vector<Vec3> points(3000);
  for (Vec3& p : points) p = Vec3(u(rng), u(rng), u(rng));
  const float r = 0.04f;
  const PointsNearSegments query(points, r);
  std::vector<PointsNearSegments::Found> found;
  size_t total = 0, nearOrigin = 0;
  for (int i = 0; i < 2000; ++i) {
    // Origins in and around the cloud; every fourth segment starts near a point and is shorter than r.
    const bool shortOne = i % 4 == 0;
    const Vec3 o = shortOne ? points[size_t(i)] + Vec3(0.01f, -0.005f, 0.002f) : Vec3(u(rng), u(rng), u(rng)) * 1.4f - 0.2f;
    Vec3 d(u(rng) - 0.5f, u(rng) - 0.5f, u(rng) - 0.5f);
    d = glm::normalize(d);
    const float length = i % 50 == 0 ? 0.0f : shortOne ? 0.5f * r * u(rng) : 1.5f * u(rng);
    query.near(o, d, length, found);
    const auto expected = bruteForce(points, r, o, d, length);
    ASSERT_EQ(found.size(), expected.size()) << "segment " << i;
    for (size_t k = 0; k < found.size(); ++k) {
      EXPECT_EQ(found[k].index, expected[k].index) << "segment " << i;
      EXPECT_NEAR(found[k].t, expected[k].t, 1e-5f) << "segment " << i;
    }
    total += found.size();
    nearOrigin += shortOne ? found.size() : 0;
  }
  // The search had points to find, also where the segment lies inside their spheres.
  EXPECT_GT(total, 3000u);
  EXPECT_GT(nearOrigin, 100u);
}

TEST(PointsNearSegments, NoPointsFindNothing) {
  const PointsNearSegments query({}, 0.1f);
  std::vector<PointsNearSegments::Found> found{{1, 1.0f}};
  query.near(Vec3(0.0f), Vec3(0.0f, 0.0f, 1.0f), 1.0f, found);
  EXPECT_TRUE(found.empty());
}

}  // namespace
}  // namespace kasha
