// Vertex merging's bias, and its vanishing as the radius shrinks (issue 14, docs/bdpt-mis.md §12), on
// a closed-form scene whose light field is not uniform over the merge disc: a fluorescent plane
// under a point light (scenes/validation/single_plane_point.json, tests/point_lit_plane.h). With a
// first radius as large as the light's height, `bpm` is far from the exact image and meets the
// image the shrinking discs blur it to; a radius that were ignored or did not shrink fails.
#include <gtest/gtest.h>

#include <cmath>

#include "tests/closed_form_support.h"
#include "tests/point_lit_plane.h"

namespace kasha {
namespace {

using namespace test;

TEST(MergeBias, QuadratureMeetsTheClosedForms) {
  auto scene = load("single_plane_point.json");
  const PointLitPlane p = pointLitPlane(*scene);
  const auto g = [&](double s) { return p.h / std::pow(p.h * p.h + s * s, 1.5); };
  // The footprint mean of g by the radial quadrature against the solid angle of the footprint.
  EXPECT_NEAR(footprintMeanRadial(p, g), footprintMeanG(p), 1e-5 * footprintMeanG(p));
  // The disc mean at the foot: 2π·(1 − h/√(h² + r²)) / (π r²); a small disc is g itself.
  for (double r : {0.3, 1.0, 2.0})
    EXPECT_NEAR(discMeanG(p.h, r, 0.0), 2.0 * (1.0 - p.h / std::sqrt(p.h * p.h + r * r)) / (r * r), 1e-5);
  for (double s : {0.0, 0.2, 0.6}) EXPECT_NEAR(discMeanG(p.h, 1e-3, s), g(s), 1e-5 * g(s));
  // The blur lowers the peak: at r_1 = h the first pass sees a third less than the exact image.
  const double exact = footprintMeanG(p), blurred = mergedMeanXyz(p, float(p.h), 2.0f / 3.0f, 1).y / p.xyzPerG.y;
  EXPECT_LT(blurred, 0.75 * exact);
}

// Mean XYZ and standard error per channel of `batches` renders of `passes` passes each.
struct Measured {
  BatchStats s[3];
};
Measured measure(const Scene& scene, const RenderSettings& settings, int passes, int batches) {
  const std::unique_ptr<Integrator> bpm = makeIntegrator("bpm", scene, settings);
  std::vector<double> c[3];
  for (const DVec3& m : batchMeans(scene, *bpm, batches, passes, 2000))
    c[0].push_back(m.x), c[1].push_back(m.y), c[2].push_back(m.z);
  return {{batchStats(c[0]), batchStats(c[1]), batchStats(c[2])}};
}

// r_1 = h = 1, α = 2/3, 256 light subpaths per pass (8 × 8 pixels; the noise is mostly the pass's
// shared wavelength lanes, bench/merge_bias/README.md), 16 batches: after 4 passes bpm is 33% below
// the exact image (13σ in Y) and within 4σ of the blur the schedule predicts; after 64 passes the
// radius has shrunk to 0.53 and the error to 17% (44σ), as predicted, while a radius that kept r_1
// would be 44σ off. Rendering with α = 0.99 or r_1 = 0.9 fails it. 2.8 s.
TEST(MergeBias, BpmMeetsTheBlurOfItsShrinkingDiscs) {
  auto scene = load("single_plane_point.json");
  const PointLitPlane p = pointLitPlane(*scene);
  RenderSettings settings = scene->render;
  settings.vcm.radius = 1.0f;
  settings.vcm.photonsPerPass = 256;
  // The prediction blurs in space only: a negligible wavelength kernel keeps the own-wavelength
  // merges through the elastic lobe from blurring in wavelength too.
  settings.vcm.bandwidth = 0.01f;
  const Vec3 exact = exactMeanXyz(p);
  for (int passes : {4, 64}) {
    // Every camera sample and light subpath of a pass shares its lanes and keeps the same one where
    // they end (docs/bdpt-mis.md §10), so a few passes see few wavelengths: more batches there.
    const Measured got = measure(*scene, settings, passes, passes == 4 ? 64 : 16);
    const Vec3 blurred = mergedMeanXyz(p, settings.vcm.radius, settings.vcm.alpha, passes);
    const Vec3 fixedRadius = mergedMeanXyz(p, settings.vcm.radius, 1.0f, passes);  // α = 1: r_i = r_1
    for (int c = 0; c < 3; ++c) {
      const BatchStats& s = got.s[c];
      SCOPED_TRACE(std::to_string(passes) + " passes, channel " + std::string(1, "XYZ"[c]));
      // The prediction's own accuracy: at 64 passes and 256 batches, Y sits 0.4% below it before
      // and after the lanes' end changed (docs/bdpt-mis.md §10), whose σ is 0.2%.
      EXPECT_NEAR(s.mean, blurred[c], 4.0 * s.stderr_ + 0.005 * blurred[c]) << "mean " << s.mean << " ± " << s.stderr_ << ", exact " << exact[c];
      // The bias is real and resolved: the exact image is many σ away, and so is the blur of a
      // radius that never shrinks.
      EXPECT_GT(std::abs(s.mean - exact[c]), 8.0 * s.stderr_);
      if (passes == 64) {
        EXPECT_GT(std::abs(s.mean - fixedRadius[c]), 8.0 * s.stderr_);
      }
    }
  }
}

}  // namespace
}  // namespace kasha
