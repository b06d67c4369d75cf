#pragma once
// Independent batch renders of a scene, summed over image regions: the mean and standard error of
// each region's X, Y and Z (docs/validation.md §4's integrator agreement tests).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <span>
#include <vector>

#include "scene/scene.h"
#include "integrators/integrator.h"
#include "integrators/render_loop.h"
#include "tests/support.h"

namespace kasha::test {

// The scene's camera, looking straight ahead from where it stands, at res × res pixels (the low
// resolution of the agreement tests).
inline void useSquareCamera(Scene& scene, int res) {
  const Camera& c = scene.camera;
  scene.camera = Camera(c.position(), c.position() + c.forward(), Vec3(0, 1, 0), c.fovYDegrees(), res, res);
}

// The scene's camera, from where it stands, turned to `target` with a vertical field of view of
// fovY degrees, at res × res pixels.
inline void aimCamera(Scene& scene, Vec3 target, float fovY, int res) {
  scene.camera = Camera(scene.camera.position(), target, Vec3(0, 1, 0), fovY, res, res);
}

// Photon mapping's and vertex merging's defaults scale with the pixel count (one photon per pixel and
// pass), far too few at the agreement tests' resolutions: a fixed number of photons per pass and
// first-pass radius (render.ppm and render.vcm).
inline void setPhotons(Scene& scene, int perPass, float radius) {
  scene.render.ppm.photonsPerPass = scene.render.vcm.photonsPerPass = perPass;
  scene.render.ppm.radius = scene.render.vcm.radius = radius;
}

// Stats of region r, channel c at index r·3 + c. Batch b uses seed seedStep·(b + 1).
inline std::vector<BatchStats> regionBatches(const Scene& scene, const Integrator& integrator, int width, int height,
                                             int regions, const std::function<int(int x, int y)>& regionOf, int spp,
                                             int batches, uint64_t seedStep) {
  std::vector<std::vector<double>> samples(size_t(regions) * 3);
  for (int b = 0; b < batches; ++b) {
    Film film(width, height);
    RenderOptions opt;
    opt.spp = spp;
    opt.seed = seedStep * uint64_t(b + 1);
    render(scene, integrator, film, opt);
    std::vector<double> sum(samples.size(), 0.0);
    for (int y = 0; y < height; ++y)
      for (int x = 0; x < width; ++x) {
        const Vec3 v = film.xyz(x, y);
        for (int ch = 0; ch < 3; ++ch) sum[size_t(regionOf(x, y) * 3 + ch)] += v[ch];
      }
    for (size_t i = 0; i < sum.size(); ++i) samples[i].push_back(sum[i]);
  }
  std::vector<BatchStats> stats;
  for (const std::vector<double>& s : samples) stats.push_back(batchStats(s));
  return stats;
}

// Expects every region and channel of `other` within k combined standard errors of `ref`, and the
// comparison to have power: a combined standard error below rel·|value| + relBrightest·(the
// brightest reference value).
inline void expectRegionsAgree(std::span<const BatchStats> ref, std::span<const BatchStats> other, double k,
                               double rel, double relBrightest) {
  double brightest = 0.0;
  for (const BatchStats& s : ref) brightest = std::max(brightest, std::abs(s.mean));
  ASSERT_GT(brightest, 0.0);
  for (size_t i = 0; i < ref.size(); ++i) {
    const double sigma = std::hypot(ref[i].stderr_, other[i].stderr_);
    EXPECT_LT(sigma, rel * std::abs(ref[i].mean) + relBrightest * brightest) << "too noisy to compare, region/channel " << i;
    EXPECT_NEAR(other[i].mean, ref[i].mean, k * sigma) << "region/channel " << i;
  }
}

}  // namespace kasha::test
