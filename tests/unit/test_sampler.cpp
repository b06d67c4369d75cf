// The sample generator (core/sampler.h): determinism per (seed, stream, sample), the net property
// of the Owen-scrambled Sobol pairs, uniformity of every dimension, and the variance reduction on
// a smooth integrand against the independent generator, with tolerances from the spread over
// independent streams.
#include <gtest/gtest.h>

#include <cmath>
#include <set>
#include <vector>

#include "core/sampler.h"

namespace kasha {
namespace {

TEST(Sampler, SobolSecondDimensionMatchesItsDirectionNumbers) {
  // Sobol's x + 1 dimension, first 8 points (Joe & Kuo's table): 0, 1/2, 3/4, 1/4, 5/8, 1/8, 3/8, 7/8.
  const double expected[] = {0.0, 0.5, 0.75, 0.25, 0.625, 0.125, 0.375, 0.875};
  for (uint32_t i = 0; i < 8; ++i) EXPECT_DOUBLE_EQ(sobol::dimension1(i) * 0x1p-32, expected[i]) << i;
  const double vdc[] = {0.0, 0.5, 0.25, 0.75, 0.125, 0.625, 0.375, 0.875};
  for (uint32_t i = 0; i < 8; ++i) EXPECT_DOUBLE_EQ(sobol::dimension0(i) * 0x1p-32, vdc[i]) << i;
}

TEST(Sampler, ReversedSecondDimensionByBytesMatchesTheBitLoop) {
  // The sampler's four-lookup form against the direction-number loop, bit-reversed by hand.
  Rng rng(5, 0);
  for (int k = 0; k < 10000; ++k) {
    const uint32_t i = k < 64 ? uint32_t(k) : rng.nextU32();
    const uint32_t d = sobol::dimension1(i);
    uint32_t reversed = 0;
    for (int b = 0; b < 32; ++b) reversed |= ((d >> b) & 1u) << (31 - b);
    ASSERT_EQ(sobol::reversedDimension1(i), reversed) << i;
  }
}

TEST(Sampler, OwenScrambleIsABijectionThatKeepsPrefixes) {
  // A nested uniform scramble maps numbers sharing their top k bits to numbers sharing their
  // top k bits, and is one-to-one.
  std::set<uint32_t> images;
  for (uint32_t v = 0; v < 4096; ++v) images.insert(sobol::owenScramble(v << 20, 12345u) >> 20);
  EXPECT_EQ(images.size(), 4096u);
  for (uint32_t v = 0; v < 1000; ++v) {
    const uint32_t a = v * 2654435761u;
    const uint32_t b = a ^ 0x0000ffffu;  // same top 16 bits
    EXPECT_EQ(sobol::owenScramble(a, 77u) >> 16, sobol::owenScramble(b, 77u) >> 16);
  }
}

TEST(Sampler, DeterminedBySeedStreamAndSample) {
  for (SamplerKind kind : {SamplerKind::Sobol, SamplerKind::Independent}) {
    Sampler a(kind, 7, 1234, 5), b(kind, 7, 1234, 5), c(kind, 8, 1234, 5), d(kind, 7, 1235, 5);
    const float a0 = a.uniform(), b0 = b.uniform();
    EXPECT_EQ(a0, b0);
    EXPECT_EQ(a.uniform2(), b.uniform2());
    EXPECT_NE(a0, c.uniform());
    EXPECT_NE(a0, d.uniform());
  }
}

// Every pair drawn with uniform2 by the first 2^k samples of a stream is a (0, k, 2)-net: each
// elementary box of area 2^-k holds exactly one point.
TEST(Sampler, PairsAreZeroKTwoNets) {
  const int k = 8;
  const uint32_t n = 1u << k;
  for (uint64_t stream : {0ull, 99ull, 123456789ull})
    for (uint32_t dim : {0u, 2u, 7u, 30u}) {
      std::vector<Vec2> pts;
      for (uint32_t s = 0; s < n; ++s) {
        Sampler sm(SamplerKind::Sobol, 42, stream, s);
        sm.setDimension(dim);
        pts.push_back(sm.uniform2());
      }
      for (int a = 0; a <= k; ++a) {
        const int bx = 1 << a, by = 1 << (k - a);
        std::vector<int> count(size_t(bx) * size_t(by), 0);
        for (const Vec2& p : pts) {
          ASSERT_GE(p.x, 0.0f);
          ASSERT_LT(p.x, 1.0f);
          ++count[size_t(int(p.y * float(by))) * size_t(bx) + size_t(int(p.x * float(bx)))];
        }
        for (int c : count) ASSERT_EQ(c, 1) << "stream " << stream << " dim " << dim << " boxes " << bx << "x" << by;
      }
    }
}

// One dimension drawn with uniform() by the first 2^k samples: one point in each interval 2^-k.
TEST(Sampler, SingleDimensionsAreStratified) {
  const uint32_t n = 512;
  for (uint32_t dim : {0u, 1u, 5u, 40u}) {
    std::vector<int> count(n, 0);
    for (uint32_t s = 0; s < n; ++s) {
      Sampler sm(SamplerKind::Sobol, 3, 77, s);
      sm.setDimension(dim);
      ++count[size_t(sm.uniform() * float(n))];
    }
    for (int c : count) ASSERT_EQ(c, 1) << "dim " << dim;
  }
}

// Across many streams, a fixed (sample, dimension) is uniform: a χ² test over 32 bins per
// dimension, and different dimensions of one sample are uncorrelated.
TEST(Sampler, EachPointIsUniformOverStreams) {
  const int bins = 32, streams = 32000;
  for (uint32_t s : {0u, 1u, 17u}) {
    std::vector<std::vector<int>> hist(4, std::vector<int>(bins, 0));
    double sxy = 0.0;
    for (int st = 0; st < streams; ++st) {
      Sampler sm(SamplerKind::Sobol, 11, uint64_t(st), s);
      const float u0 = sm.uniform();
      const Vec2 p = sm.uniform2();
      const float u3 = sm.uniform();
      const float u[4] = {u0, p.x, p.y, u3};
      for (int d = 0; d < 4; ++d) ++hist[size_t(d)][size_t(u[d] * bins)];
      sxy += (double(p.x) - 0.5) * (double(p.y) - 0.5);
    }
    const double expected = double(streams) / bins;
    for (int d = 0; d < 4; ++d) {
      double chi2 = 0.0;
      for (int c : hist[size_t(d)]) chi2 += (c - expected) * (c - expected) / expected;
      // 31 degrees of freedom: P(χ² > 70) ≈ 1e-4.
      EXPECT_LT(chi2, 70.0) << "sample " << s << " dim " << d;
    }
    // Correlation of x and y: variance of each term 1/144, so the standard error is
    // sqrt(1/144/streams); 5 standard errors.
    EXPECT_LT(std::abs(sxy / streams), 5.0 * std::sqrt(1.0 / 144.0 / streams)) << "sample " << s;
  }
}

// On a smooth 2D integrand, 256 scrambled Sobol samples have a far smaller error than 256
// independent ones; both are unbiased. Errors are measured over 400 independent streams.
TEST(Sampler, SobolBeatsIndependentOnASmoothIntegrand) {
  auto f = [](Vec2 u) { return std::exp(-double(u.x)) * std::cos(double(u.y)); };
  const double exact = (1.0 - std::exp(-1.0)) * std::sin(1.0);
  const int n = 256, streams = 400;
  double mse[2] = {0, 0}, bias[2] = {0, 0};
  for (int k = 0; k < 2; ++k) {
    const SamplerKind kind = k == 0 ? SamplerKind::Sobol : SamplerKind::Independent;
    for (int st = 0; st < streams; ++st) {
      double sum = 0.0;
      for (int s = 0; s < n; ++s) {
        Sampler sm(kind, 5, uint64_t(st), uint32_t(s));
        sm.uniform();  // a dimension before, as a pixel's wavelength would be
        sum += f(sm.uniform2());
      }
      const double e = sum / n - exact;
      mse[k] += e * e / streams;
      bias[k] += e / streams;
    }
  }
  for (int k = 0; k < 2; ++k) EXPECT_LT(std::abs(bias[k]), 4.0 * std::sqrt(mse[k] / streams)) << k;
  // Independent: variance of f over the square / n; scrambled Sobol: O(n^-3 log n) for smooth f.
  EXPECT_LT(mse[0], mse[1] / 50.0);
}

}  // namespace
}  // namespace kasha
