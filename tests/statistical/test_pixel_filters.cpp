// Pixel reconstruction filters (core/pixel_filter.h) are unbiased in every kind of estimator:
// - A quarter-plane emitter whose edges lie on pixel boundaries is piecewise constant per pixel, so
//   the box filter's image B convolves exactly into any filter's: pixel k's value is
//   Σ_i B_i·∫_{pixel i} f(x − c_k) dx / ∫f. A Gaussian render by filter importance sampling (pt)
//   and by splats (lt) agrees with the box render so convolved, pixel by pixel within 4 standard
//   errors; the box render itself and its convolution with the tent are both rejected (the
//   comparison has power).
// - On the fluorescent Cornell box, lt's splats and bdpt agree with pt's filter-importance-sampled
//   samples with a tent filter wider than a pixel, region by region, edges included.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <vector>

#include "integrators/render_loop.h"
#include "scene/scene_loader.h"
#include "tests/integrator_names.h"
#include "tests/region_batches.h"
#include "tests/support.h"

namespace kasha {
namespace {

constexpr int kW = 16, kH = 8;

// Camera at 2 in front of the plane z = 0, looking along +z, 16 × 8 pixels; the image's right is
// −x and its top +y, so the emitter on x > 0, y > 0 fills the top-left quadrant, its edges on the
// boundaries of columns 7|8 and rows 3|4. It reaches beyond the image by more than the filters'
// margin (1.5 pixels), so that the scene beyond each edge continues the edge's pixels.
constexpr const char* kQuarterPlane = R"({
  "camera": {"position": [0, 0, -2], "look_at": [0, 0, 0], "fov": 40, "resolution": [16, 8]},
  "materials": {"black": {"type": "lambertian", "reflectance": 0}},
  "shapes": [{"type": "rectangle", "center": [1, 0.6, 0], "u": [0, 0.6, 0], "v": [1, 0, 0],
              "material": "black", "emission": {"radiance": 1}}]
})";

std::unique_ptr<Scene> quarterPlane(const PixelFilter& filter) {
  auto scene = loadSceneFromString(kQuarterPlane, test::sourcePath("tests/quarter_plane.json"));
  scene->pixelFilter = filter;
  return scene;
}

// Y per pixel of each batch render.
std::vector<std::vector<double>> batchImages(const Scene& scene, const std::string& integrator, int spp, int batches,
                                             uint64_t seed) {
  const auto in = test::makeTestIntegrator(integrator, scene, scene.render);
  std::vector<std::vector<double>> out;
  for (int b = 0; b < batches; ++b) {
    Film film(kW, kH);
    RenderOptions opt;
    opt.spp = spp;
    opt.seed = seed + uint64_t(b);
    // Independent samples: Sobol's nets place nearly the same count of samples beyond a straight
    // edge in every batch, so batches would understate the error of a pixel's mean.
    opt.sampler = SamplerKind::Independent;
    render(scene, *in, film, opt);
    std::vector<double> y(size_t(kW * kH));
    for (int py = 0; py < kH; ++py)
      for (int px = 0; px < kW; ++px) y[size_t(py * kW + px)] = film.xyz(px, py).y;
    out.push_back(y);
  }
  return out;
}

// The filter's mass over pixel i seen from pixel k's centre (i − k = d), per axis: ∫_{d−1/2}^{d+1/2} g
// / ∫g, g written out here from Mitsuba 3's documentation.
std::vector<double> pixelMasses(const std::function<double(double)>& g, int reach) {
  const auto integral = [&](double a, double b) {
    const int n = 4000;
    double s = 0.0;
    for (int i = 0; i < n; ++i) s += g(a + (i + 0.5) * (b - a) / n);
    return s * (b - a) / n;
  };
  const double total = integral(-reach - 0.5, reach + 0.5);
  std::vector<double> m;
  for (int d = -reach; d <= reach; ++d) m.push_back(integral(d - 0.5, d + 0.5) / total);
  return m;
}

// The box image convolved with the separable filter whose per-pixel masses are m (pixels beyond
// the image continue its edge, as the scene does).
std::vector<double> convolve(const std::vector<double>& box, const std::vector<double>& m) {
  const int reach = int(m.size() / 2);
  std::vector<double> out(box.size(), 0.0);
  for (int ky = 0; ky < kH; ++ky)
    for (int kx = 0; kx < kW; ++kx)
      for (int dy = -reach; dy <= reach; ++dy)
        for (int dx = -reach; dx <= reach; ++dx) {
          const int x = std::clamp(kx + dx, 0, kW - 1), y = std::clamp(ky + dy, 0, kH - 1);
          out[size_t(ky * kW + kx)] += box[size_t(y * kW + x)] * m[size_t(dx + reach)] * m[size_t(dy + reach)];
        }
  return out;
}

// Each group's sum (group[p] of pixel p) over the batches: its mean and standard error.
std::vector<test::BatchStats> groupStats(const std::vector<std::vector<double>>& batches, const std::vector<int>& group) {
  const int groups = *std::max_element(group.begin(), group.end()) + 1;
  std::vector<std::vector<double>> sums(size_t(groups), std::vector<double>(batches.size(), 0.0));
  for (size_t b = 0; b < batches.size(); ++b)
    for (size_t p = 0; p < group.size(); ++p) sums[size_t(group[p])][b] += batches[b][p];
  std::vector<test::BatchStats> s;
  for (const std::vector<double>& v : sums) s.push_back(test::batchStats(v));
  return s;
}

// The largest |a − b| over the combined standard error. The emitter's radiance is flat, so its
// inside has no noise at all: the error there is the film's float rounding, of values of order 1.
constexpr double kRounding = 1e-5;
double worstSigma(const std::vector<test::BatchStats>& a, const std::vector<test::BatchStats>& b) {
  double worst = 0.0;
  for (size_t p = 0; p < a.size(); ++p)
    worst = std::max(worst, std::abs(a[p].mean - b[p].mean) / (std::hypot(a[p].stderr_, b[p].stderr_) + kRounding));
  return worst;
}

double gaussianProfile(double x) {
  const double s = 0.5, r = 4.0 * s;
  return std::abs(x) < r ? std::exp(-x * x / (2.0 * s * s)) - std::exp(-r * r / (2.0 * s * s)) : 0.0;
}

TEST(PixelFilters, GaussianRenderIsTheBoxRenderConvolvedWithTheFilter) {
  constexpr int kBatches = 16, kSpp = 128;
  const auto box = quarterPlane(PixelFilter());
  const std::vector<std::vector<double>> boxBatches = batchImages(*box, "pt", 64, kBatches, 100);
  const std::vector<double> gauss = pixelMasses(gaussianProfile, 2);
  const std::vector<double> tent = pixelMasses([](double x) { return std::max(0.0, 1.0 - std::abs(x)); }, 1);
  std::vector<std::vector<double>> predicted, tentPredicted;
  for (const auto& b : boxBatches) {
    predicted.push_back(convolve(b, gauss));
    tentPredicted.push_back(convolve(b, tent));
  }
  // A pixel's samples see the emitter (Y = 1) or not (Y = 0). Pixels are compared one by one where
  // both outcomes are expected at least 20 times in the pt renders; the others, where a batch may
  // see no rare outcome at all (and its standard error would be 0), in two sums, the dim and the
  // bright.
  const std::vector<double>& expected = predicted[0];
  const double samples = double(kBatches) * kSpp;
  std::vector<int> group(expected.size(), -1);
  int groups = 0;
  for (size_t p = 0; p < expected.size(); ++p) {
    const double e = expected[p] / expected[0];
    if (std::min(e, 1.0 - e) * samples >= 20.0) group[p] = groups++;
  }
  for (size_t p = 0; p < expected.size(); ++p)
    if (group[p] < 0) group[p] = groups + (expected[p] < 0.5 * expected[0] ? 0 : 1);
  const auto prediction = groupStats(predicted, group);
  // The emitter's inside, far from its edges, is the same with any filter; its corner pixel is
  // dimmed by the filter reaching across both edges.
  EXPECT_GT(expected[0], 0.0);
  EXPECT_LT(expected[3 * kW + 7], 0.8 * expected[0]);
  const auto gaussian = quarterPlane(PixelFilter::gaussian(0.5f));
  for (const char* integrator : {"pt", "lt"}) {
    SCOPED_TRACE(integrator);
    const auto rendered = groupStats(batchImages(*gaussian, integrator, std::string(integrator) == "lt" ? 2 * kSpp : kSpp, kBatches, 900), group);
    EXPECT_LT(worstSigma(rendered, prediction), 4.0);
    EXPECT_GT(worstSigma(rendered, groupStats(boxBatches, group)), 8.0);
    EXPECT_GT(worstSigma(rendered, groupStats(tentPredicted, group)), 5.0);
  }
}

TEST(PixelFilters, LightTracingSplatsAgreeWithFilterImportanceSampling) {
  constexpr int kRes = 16, kRegions = 2;
  auto scene = loadScene(test::sourcePath("scenes/cornell_fluorescent.json"));
  test::useSquareCamera(*scene, kRes);
  scene->pixelFilter = PixelFilter::tent(1.5f);
  RenderSettings settings = scene->render;
  settings.maxDepth = 6;
  // Quadrants, and the ring of pixels within the filter's reach of the image's edges.
  const auto regionOf = [](int x, int y) {
    if (x < 2 || y < 2 || x >= kRes - 2 || y >= kRes - 2) return kRegions * kRegions;
    return (y * kRegions / kRes) * kRegions + x * kRegions / kRes;
  };
  const auto estimate = [&](const std::string& name, int spp) {
    const auto in = test::makeTestIntegrator(name, *scene, settings);
    return test::regionBatches(*scene, *in, kRes, kRes, kRegions * kRegions + 1, regionOf, spp, 12, 4099);
  };
  const std::vector<test::BatchStats> pt = estimate("pt", 32);
  for (const char* other : {"lt", "bdpt"}) {
    SCOPED_TRACE(other);
    test::expectRegionsAgree(pt, estimate(other, 16), 4.0, 0.1, 0.02);
  }
}

}  // namespace
}  // namespace kasha
