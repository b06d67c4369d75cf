#include "integrators/bdpt/family_pilot.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

namespace kasha::bdpt {
namespace {

constexpr int kImages = 4;  // estimator a's two images, then b's
// Camera samples per image at least: small images take several per pixel.
constexpr size_t kMinSamplesPerImage = 16384;

using Image = std::vector<std::array<double, 3>>;

void add(Image& img, size_t i, const Vec3& v, double scale) {
  if (!(std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z))) return;
  img[i][0] += scale * v.x, img[i][1] += scale * v.y, img[i][2] += scale * v.z;
}

// The 5×5 box mean (clipped at the borders) of the sum of the images, divided by their count.
std::vector<std::array<double, 3>> boxMean(const std::array<Image, kImages>& images, int w, int h) {
  constexpr int r = 2;
  std::vector<std::array<double, 3>> mean(size_t(w) * size_t(h));
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      std::array<double, 3> s{};
      int n = 0;
      for (int yy = std::max(0, y - r); yy <= std::min(h - 1, y + r); ++yy)
        for (int xx = std::max(0, x - r); xx <= std::min(w - 1, x + r); ++xx, ++n)
          for (const Image& img : images)
            for (int c = 0; c < 3; ++c) s[c] += img[size_t(yy) * w + xx][c];
      for (int c = 0; c < 3; ++c) mean[size_t(y) * w + x][c] = s[c] / double(n * kImages);
    }
  return mean;
}

// The mean of the values without the 0.01% largest.
double trimmedMean(std::vector<double> v) {
  const size_t drop = (v.size() + 9999) / 10000, keep = v.size() - std::min(drop, v.size());
  if (keep == 0) return 0.0;
  std::nth_element(v.begin(), v.begin() + ptrdiff_t(keep - 1), v.end());
  double s = 0.0;
  for (size_t i = 0; i < keep; ++i) s += v[i];
  return s / double(keep);
}

// Whether the means of estimators a and b (images 0, 1 and 2, 3) agree in every 16×16 region and
// channel within 5 standard errors, the pixels' variances from their two images.
bool regionsAgree(const std::array<Image, kImages>& images, int w, int h) {
  constexpr int kRegion = 16;
  for (int y0 = 0; y0 < h; y0 += kRegion)
    for (int x0 = 0; x0 < w; x0 += kRegion)
      for (int c = 0; c < 3; ++c) {
        double diff = 0.0, var = 0.0, scale = 0.0;
        for (int y = y0; y < std::min(h, y0 + kRegion); ++y)
          for (int x = x0; x < std::min(w, x0 + kRegion); ++x) {
            const size_t i = size_t(y) * w + x;
            const double a1 = images[0][i][c], a2 = images[1][i][c], b1 = images[2][i][c], b2 = images[3][i][c];
            diff += 0.5 * (a1 + a2) - 0.5 * (b1 + b2);
            // Var of each two-sample mean: (x₁ − x₂)²/4.
            var += 0.25 * ((a1 - a2) * (a1 - a2) + (b1 - b2) * (b1 - b2));
            scale += std::abs(a1) + std::abs(a2) + std::abs(b1) + std::abs(b2);
          }
        if (std::abs(diff) > 5.0 * std::sqrt(var) && std::abs(diff) > 1e-6 * scale) return false;
      }
  return true;
}

}  // namespace

PilotVariances pilotVariances(int w, int h, uint64_t seed, SamplerKind kind, const PilotSample& sample) {
  const size_t pixels = size_t(w) * size_t(h);
  const int n = int((kMinSamplesPerImage + pixels - 1) / pixels);  // samples per pixel of each image
  const double scale = 1.0 / n;
  std::array<Image, kImages> images;
  for (Image& img : images) img.assign(pixels, {0.0, 0.0, 0.0});
  // Per row and image, its splats: added in row order, so the result does not depend on scheduling.
  std::vector<std::array<SampleContext, kImages>> rows{size_t(h)};
  std::vector<std::vector<Splat>> rowExcess{size_t(h)};
  const uint64_t pilotSeed = seed * 0x9E3779B97F4A7C15ull + 0x2545F4914F6CDD1Dull;
  tbb::parallel_for(0, h, [&](int y) {
    std::array<SampleContext, kImages>& ctx = rows[size_t(y)];
    for (int x = 0; x < w; ++x)
      for (int pass = 0; pass < 2; ++pass)
        for (int j = 0; j < n; ++j) {
          const size_t i = size_t(y) * w + x;
          Sampler rng(kind, pilotSeed, uint64_t(i), uint32_t(pass * n + j));
          const auto [va, vb] = sample(Vec2(float(x), float(y)), rng, ctx[pass], ctx[2 + pass], rowExcess[size_t(y)]);
          add(images[pass], i, va, scale);
          add(images[2 + pass], i, vb, scale);
        }
  });
  PilotVariances out;
  for (std::array<SampleContext, kImages>& ctx : rows)
    for (int k = 0; k < kImages; ++k) {
      out.rays.closest += ctx[k].counter.closest;
      out.rays.shadow += ctx[k].counter.shadow;
      for (const Splat& s : ctx[k].splats) {
        if (!std::isfinite(s.pixel.x) || !std::isfinite(s.pixel.y)) continue;
        const int x = int(std::clamp(s.pixel.x, 0.0f, float(w - 1))), y = int(std::clamp(s.pixel.y, 0.0f, float(h - 1)));
        add(images[k], size_t(y) * w + x, s.xyz, scale);
      }
    }
  Image excess(pixels, {0.0, 0.0, 0.0});
  for (const std::vector<Splat>& row : rowExcess)
    for (const Splat& s : row) {
      if (!std::isfinite(s.pixel.x) || !std::isfinite(s.pixel.y)) continue;
      const int x = int(std::clamp(s.pixel.x, 0.0f, float(w - 1))), y = int(std::clamp(s.pixel.y, 0.0f, float(h - 1)));
      add(excess, size_t(y) * w + x, s.xyz, 0.5 * scale);  // per sample: over the 2n of each pixel
    }
  out.agree = regionsAgree(images, w, h);
  const std::vector<std::array<double, 3>> mean = boxMean(images, w, h);
  for (size_t i = 0; i < pixels; ++i)
    for (int c = 0; c < 3; ++c) out.excess += excess[i][c] / (mean[i][c] * mean[i][c] + 1e-2) / double(pixels);
  for (int e = 0; e < 2; ++e) {
    std::vector<double> rel(pixels, 0.0);
    for (size_t i = 0; i < pixels; ++i)
      for (int c = 0; c < 3; ++c) {
        const double d = images[2 * e][i][c] - images[2 * e + 1][i][c];
        rel[i] += n * 0.5 * d * d / (mean[i][c] * mean[i][c] + 1e-2);  // per sample: n × the mean's
      }
    (e == 0 ? out.a : out.b) = trimmedMean(std::move(rel));
  }
  return out;
}

}  // namespace kasha::bdpt
