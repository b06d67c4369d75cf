// The photon map (integrators/photon_mapping/photon_map.h): FLANN's radius queries against brute
// force on random points, with one tree and with the cells of a large map, and FLANN's memory
// against the bytes per photon the memory limit uses.
#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

#include "core/rng.h"
#include "core/sampling.h"
#include "integrators/photon_mapping/photon_map.h"

namespace kasha {
namespace {

std::vector<Photon> randomPhotons(size_t n, Rng& rng, bool onSphere) {
  std::vector<Photon> v(n);
  for (size_t i = 0; i < n; ++i) {
    const Vec3 p = onSphere ? sampleUniformSphere(Vec2(rng.uniform(), rng.uniform()))
                            : Vec3(rng.uniform(), rng.uniform(), rng.uniform()) * 2.0f - 1.0f;
    // The first lane's wavelength is the photon's name here (exact in a float below 2^24).
    v[i] = {{p.x, p.y, p.z}, {0.0f, 0.0f, 1.0f}, 1, 1, false, {float(i)}, {1.0f}};
  }
  return v;
}

// Points whose squared distance lies within this relative margin of r² may be decided either way
// by rounding, so they are left out of the comparison.
bool borderline(float d2, float r2) { return std::abs(d2 - r2) <= 1e-5f * r2; }

void compareWithBruteForce(size_t n, bool onSphere, uint64_t seed) {
  Rng rng(seed);
  std::vector<Photon> photons = randomPhotons(n, rng, onSphere);
  const std::vector<Photon> copy = photons;
  const PhotonMap map(std::move(photons));
  ASSERT_EQ(map.size(), n);
  EXPECT_EQ(map.cells(), n >= PhotonMap::kSplitFrom ? size_t(1) << PhotonMap::kSplitLevels : 1u);
  size_t found = 0;
  for (int q = 0; q < 200; ++q) {
    const Vec3 x = onSphere ? sampleUniformSphere(Vec2(rng.uniform(), rng.uniform()))
                            : Vec3(rng.uniform(), rng.uniform(), rng.uniform()) * 2.4f - 1.2f;
    const float r = 0.02f + 0.6f * rng.uniform() * rng.uniform();
    std::vector<size_t> got, expected;  // the photons' names (the map reorders them)
    for (const size_t i : map.within(x, r)) got.push_back(size_t(map[i].lambda[0]));
    for (size_t i = 0; i < n; ++i) {
      const Vec3 d = Vec3(copy[i].p[0], copy[i].p[1], copy[i].p[2]) - x;
      const float d2 = glm::dot(d, d);
      if (borderline(d2, r * r)) {
        got.erase(std::remove(got.begin(), got.end(), i), got.end());
        continue;
      }
      if (d2 < r * r) expected.push_back(i);
    }
    std::sort(got.begin(), got.end());
    EXPECT_EQ(got, expected) << "query " << q << " radius " << r;
    found += expected.size();
  }
  EXPECT_GT(found, 0u);
}

TEST(PhotonMap, RadiusQueriesMatchBruteForceInACube) {
  for (size_t n : {1, 7, 10, 11, 100, 5000, 40000}) compareWithBruteForce(n, false, 11 + n);
}

TEST(PhotonMap, RadiusQueriesMatchBruteForceOnASphere) {
  for (size_t n : {3, 64, 4000, 40000}) compareWithBruteForce(n, true, 29 + n);
}

TEST(PhotonMap, EmptyMapFindsNothing) {
  const PhotonMap map({});
  EXPECT_TRUE(map.within(Vec3(0.0f), 1.0f).empty());
}

TEST(PhotonMap, TreeFitsTheBytesPerPhotonOfTheMemoryLimit) {
  // FLANN's usedMemory() counts its node pool and permutation array; the reordered positions and
  // the row pointers (12 + 8 bytes per point) come on top.
  Rng rng(5);
  for (size_t n : {1000, 100000}) {
    const PhotonMap map(randomPhotons(n, rng, true));
    EXPECT_LE(map.treeBytes() + 20 * n, kIndexBytesPerPhoton * n + 16384) << n << " photons";
  }
}

}  // namespace
}  // namespace kasha
