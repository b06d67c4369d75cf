// Pixel reconstruction filters (core/pixel_filter.h) against the filters written out here from
// Mitsuba 3's documentation: camera samples' offsets are distributed as the normalised filter (χ²),
// the box reproduces pixel + u, splat weights are the normalised filter at each pixel centre, and
// the camera samples' coverage integrates to the pixel count.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <vector>

#include "core/pixel_filter.h"
#include "core/rng.h"
#include "tests/support.h"

namespace kasha {
namespace {

// The filters' profiles g(x), written from Mitsuba 3's documentation (not from the class).
double tentProfile(double x, double r) { return std::max(0.0, 1.0 - std::abs(x) / r); }
double gaussianProfile(double x, double s) {
  const double r = 4.0 * s;
  return std::abs(x) < r ? std::exp(-x * x / (2.0 * s * s)) - std::exp(-r * r / (2.0 * s * s)) : 0.0;
}

struct Case {
  PixelFilter filter;
  std::function<double(double)> profile;
};

std::vector<Case> cases() {
  return {{PixelFilter::tent(1.0f), [](double x) { return tentProfile(x, 1.0); }},
          {PixelFilter::tent(1.25f), [](double x) { return tentProfile(x, 1.25); }},
          {PixelFilter::gaussian(0.5f), [](double x) { return gaussianProfile(x, 0.5); }},
          {PixelFilter::gaussian(0.3f), [](double x) { return gaussianProfile(x, 0.3); }}};
}

// ∫ g over [a, b] by the midpoint rule.
double integral(const std::function<double(double)>& g, double a, double b, int n = 2000) {
  double sum = 0.0;
  for (int i = 0; i < n; ++i) sum += g(a + (i + 0.5) * (b - a) / n);
  return sum * (b - a) / n;
}

TEST(PixelFilter, CameraSampleOffsetsFollowTheNormalisedFilter) {
  constexpr int kBins = 12, kSamples = 200000;
  for (const Case& c : cases()) {
    SCOPED_TRACE(std::string(c.filter.name()) + " radius " + std::to_string(c.filter.radius()));
    const double r = c.filter.radius(), width = 2.0 * r / kBins;
    // The separable filter's mass in each cell: products of the profile's mass in each 1D bin.
    std::vector<double> mass(kBins);
    const double total = integral(c.profile, -r, r, 20000);
    for (int i = 0; i < kBins; ++i) mass[size_t(i)] = integral(c.profile, -r + i * width, -r + (i + 1) * width) / total;
    std::vector<double> observed(kBins * kBins, 0.0), expected(kBins * kBins);
    for (int j = 0; j < kBins; ++j)
      for (int i = 0; i < kBins; ++i) expected[size_t(j * kBins + i)] = kSamples * mass[size_t(i)] * mass[size_t(j)];
    Rng rng(1234);
    const Vec2 pixel(3.0f, 5.0f);
    for (int k = 0; k < kSamples; ++k) {
      const float ux = rng.uniform(), uy = rng.uniform();
      const Vec2 offset = c.filter.filmPosition(pixel, Vec2(ux, uy)) - pixel - Vec2(0.5f);
      ASSERT_LT(std::abs(offset.x), r);
      ASSERT_LT(std::abs(offset.y), r);
      const int i = std::min(int((offset.x + r) / width), kBins - 1), j = std::min(int((offset.y + r) / width), kBins - 1);
      observed[size_t(j * kBins + i)] += 1.0;
    }
    EXPECT_GT(test::chi2PValue(observed, expected), 1e-4);
    // The density is the normalised filter.
    for (const float x : {0.0f, 0.3f, -0.7f, 1.1f})
      EXPECT_NEAR(c.filter.density(Vec2(x, 0.2f)), c.profile(x) * c.profile(0.2) / (total * total), 1e-5);
  }
}

TEST(PixelFilter, SamplesStayInsideTheSupportWhereTheDensityIsPositive) {
  for (const Case& c : cases())
    for (const float u : {0.0f, 0x1p-24f, 0.5f, 1.0f - 0x1p-24f}) {
      const Vec2 offset = c.filter.filmPosition(Vec2(0.0f), Vec2(u, u)) - Vec2(0.5f);
      EXPECT_GT(c.filter.density(offset), 0.0f) << c.filter.name() << " u = " << u;
    }
}

TEST(PixelFilter, BoxIsPixelPlusUniformJitterAndOneSplat) {
  const PixelFilter box;
  EXPECT_EQ(box.type(), PixelFilterType::Box);
  EXPECT_EQ(box.filmMargin(), 0.0f);
  Rng rng(5);
  for (int k = 0; k < 100; ++k) {
    const Vec2 pixel(float(k % 7), float(k / 7)), u(rng.uniform(), rng.uniform());
    const Vec2 film = box.filmPosition(pixel, u);
    EXPECT_EQ(film.x, pixel.x + u.x);
    EXPECT_EQ(film.y, pixel.y + u.y);
    int calls = 0;
    box.splat(film, 7, 15, [&](int x, int y, float w) {
      ++calls;
      EXPECT_EQ(x, int(pixel.x));
      EXPECT_EQ(y, int(pixel.y));
      EXPECT_EQ(w, 1.0f);
    });
    EXPECT_EQ(calls, 1);
    EXPECT_EQ(box.coverage(film, 7, 15), 1.0f);
  }
  EXPECT_EQ(box.coverage(Vec2(-0.1f, 3.0f), 7, 15), 0.0f);
}

TEST(PixelFilter, SplatWeightsAreTheNormalisedFilterAtEachPixelCentre) {
  const int w = 9, h = 6;
  for (const Case& c : cases()) {
    SCOPED_TRACE(c.filter.name());
    const double total = integral(c.profile, -c.filter.radius(), c.filter.radius(), 20000);
    Rng rng(77);
    for (int k = 0; k < 50; ++k) {
      // Positions over the image and its margin.
      const float m = c.filter.filmMargin();
      const Vec2 x(-m + rng.uniform() * (w + 2 * m), -m + rng.uniform() * (h + 2 * m));
      std::vector<double> got(size_t(w * h), 0.0);
      double sum = 0.0;
      c.filter.splat(x, w, h, [&](int px, int py, float weight) {
        ASSERT_TRUE(px >= 0 && px < w && py >= 0 && py < h);
        got[size_t(py * w + px)] += weight;
        sum += weight;
      });
      for (int py = 0; py < h; ++py)
        for (int px = 0; px < w; ++px) {
          const double want = c.profile(x.x - (px + 0.5)) * c.profile(x.y - (py + 0.5)) / (total * total);
          EXPECT_NEAR(got[size_t(py * w + px)], want, 1e-5) << px << ", " << py;
        }
      EXPECT_NEAR(c.filter.coverage(x, w, h), sum, 1e-5);
    }
  }
  // The tent of radius 1 is a partition of unity: inside the image its coverage is 1 exactly.
  EXPECT_NEAR(PixelFilter::tent(1.0f).coverage(Vec2(4.3f, 2.9f), w, h), 1.0f, 1e-6f);
}

// Every pixel's normalised filter integrates to 1, so the coverage (their sum) integrates to the
// pixel count over the image and its margin.
TEST(PixelFilter, CoverageIntegratesToThePixelCount) {
  const int w = 4, h = 3, n = 400;
  for (const Case& c : cases()) {
    const float m = c.filter.filmMargin() + 0.5f;
    const double dx = (w + 2.0 * m) / n, dy = (h + 2.0 * m) / n;
    double sum = 0.0;
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i)
        sum += c.filter.coverage(Vec2(float(-m + (i + 0.5) * dx), float(-m + (j + 0.5) * dy)), w, h) * dx * dy;
    EXPECT_NEAR(sum, double(w * h), 2e-3 * w * h) << c.filter.name();
  }
}

}  // namespace
}  // namespace kasha
