#include "integrators/bdpt/family_pilot.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cmath>

namespace kasha::bdpt {
namespace {

// Camera samples per image at least: small images take several per pixel.
constexpr size_t kMinSamplesPerImage = 16384;

using Image = std::vector<std::array<double, 3>>;

void add(Image& img, size_t i, const Vec3& v, double scale) {
  if (!(std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z))) return;
  img[i][0] += scale * v.x, img[i][1] += scale * v.y, img[i][2] += scale * v.z;
}

// Adds splat-like values (film positions) to `img`; those at a non-finite position are dropped.
void addAt(Image& img, int w, int h, const std::vector<Splat>& values, double scale) {
  for (const Splat& s : values) {
    if (!std::isfinite(s.pixel.x) || !std::isfinite(s.pixel.y)) continue;
    const int x = int(std::clamp(s.pixel.x, 0.0f, float(w - 1))), y = int(std::clamp(s.pixel.y, 0.0f, float(h - 1)));
    add(img, size_t(y) * w + x, s.xyz, scale);
  }
}

// The 5×5 box mean (clipped at the borders) of the mean of the two images.
Image boxMean(const std::array<Image, 2>& images, int w, int h) {
  constexpr int r = 2;
  Image mean(size_t(w) * size_t(h));
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      std::array<double, 3> s{};
      int n = 0;
      for (int yy = std::max(0, y - r); yy <= std::min(h - 1, y + r); ++yy)
        for (int xx = std::max(0, x - r); xx <= std::min(w - 1, x + r); ++xx, ++n)
          for (const Image& img : images)
            for (int c = 0; c < 3; ++c) s[c] += img[size_t(yy) * w + xx][c];
      for (int c = 0; c < 3; ++c) mean[size_t(y) * w + x][c] = s[c] / double(2 * n);
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

}  // namespace

PilotEstimates pilotEstimates(int w, int h, uint64_t seed, SamplerKind kind, const PilotSample& sample) {
  const size_t pixels = size_t(w) * size_t(h);
  const int n = int((kMinSamplesPerImage + pixels - 1) / pixels);  // samples per pixel of each image
  const double scale = 1.0 / n;
  std::array<Image, 2> images;
  for (Image& img : images) img.assign(pixels, {0.0, 0.0, 0.0});
  // Per row and image, its splats and excess: added in row order, so the result does not depend
  // on scheduling.
  std::vector<std::array<SampleContext, 2>> rows{size_t(h)};
  std::vector<std::vector<Splat>> rowExcess{size_t(h)};
  const uint64_t pilotSeed = seed * 0x9E3779B97F4A7C15ull + 0x2545F4914F6CDD1Dull;
  tbb::parallel_for(0, h, [&](int y) {
    for (int x = 0; x < w; ++x)
      for (int image = 0; image < 2; ++image)
        for (int j = 0; j < n; ++j) {
          const size_t i = size_t(y) * w + x;
          Sampler rng(kind, pilotSeed, uint64_t(i), uint32_t(image * n + j));
          add(images[image], i, sample(Vec2(float(x), float(y)), rng, rows[size_t(y)][image], rowExcess[size_t(y)]), scale);
        }
  });
  PilotEstimates out;
  Image excess(pixels, {0.0, 0.0, 0.0});
  for (int y = 0; y < h; ++y) {
    for (int image = 0; image < 2; ++image) {
      const SampleContext& ctx = rows[size_t(y)][image];
      out.rays.closest += ctx.counter.closest;
      out.rays.shadow += ctx.counter.shadow;
      addAt(images[image], w, h, ctx.splats, scale);
    }
    addAt(excess, w, h, rowExcess[size_t(y)], 0.5 * scale);  // per sample: over the 2n of each pixel
  }
  const Image mean = boxMean(images, w, h);
  std::vector<double> rel(pixels, 0.0);
  for (size_t i = 0; i < pixels; ++i)
    for (int c = 0; c < 3; ++c) {
      const double d = images[0][i][c] - images[1][i][c], m2 = mean[i][c] * mean[i][c] + 1e-2;
      rel[i] += n * 0.5 * d * d / m2;  // per sample: n × the mean's
      out.relExcess += excess[i][c] / m2 / double(pixels);
    }
  out.relVar = trimmedMean(std::move(rel));
  return out;
}

}  // namespace kasha::bdpt
