#include "integrators/bidirectional/family_pilot.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <string>

namespace kasha::bidir {
namespace {

// Camera samples per image at least: small images take several per pixel.
constexpr size_t kMinSamplesPerImage = 8192;

using Image = std::vector<std::array<double, 3>>;

void add(Image& img, size_t i, const Vec3& v, double scale) {
  if (!(std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z))) return;
  img[i][0] += scale * v.x, img[i][1] += scale * v.y, img[i][2] += scale * v.z;
}

// Adds splat-like values (film positions) to the cells of qx × qy pixels of `img` (w × h cells);
// those at a non-finite position are dropped.
void addAt(Image& img, int w, int h, int qx, int qy, const std::vector<Splat>& values, double scale) {
  for (const Splat& s : values) {
    if (!std::isfinite(s.pixel.x) || !std::isfinite(s.pixel.y)) continue;
    const int x = std::clamp(int(s.pixel.x) / qx, 0, w - 1), y = std::clamp(int(s.pixel.y) / qy, 0, h - 1);
    add(img, size_t(y) * w + x, s.xyz, scale);
  }
}

// The stand-in for the reference at each cell: the mean of both images over the 5×5 cells around it
// (clipped at the borders), the cell itself left out, so that a cell's variance and the mean it is
// divided by are independent. With the cell in its own mean, a rare large sample X raised that mean
// by X/50 and so capped its own relative variance near 50²/2, whatever X: the variance of an
// estimator with rare large samples (camera paths reaching a small light through glass) came out
// several times too low. An image of one cell keeps it.
Image neighbourMean(const std::array<Image, 2>& images, int w, int h) {
  constexpr int r = 2;
  Image mean(size_t(w) * size_t(h));
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      std::array<double, 3> s{};
      int n = 0;  // the other cells
      for (int yy = std::max(0, y - r); yy <= std::min(h - 1, y + r); ++yy)
        for (int xx = std::max(0, x - r); xx <= std::min(w - 1, x + r); ++xx) {
          if (xx == x && yy == y) continue;
          ++n;
          for (const Image& img : images)
            for (int c = 0; c < 3; ++c) s[c] += img[size_t(yy) * w + xx][c];
        }
      const size_t i = size_t(y) * w + x;
      for (int c = 0; c < 3; ++c)
        mean[i][c] = n > 0 ? s[c] / double(2 * n) : 0.5 * (images[0][i][c] + images[1][i][c]);
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

// The cells of qx × qy pixels a pilot samples, w × h of them, each at its centre pixel: with
// r = pixels / 8192, qy = ⌊√r⌋ and qx = ⌊r / qy⌋ (at least 1), so that there are at least 8192.
struct Cells {
  int qx, qy, w, h;
  Cells(int width, int height) {
    const double r = double(width) * double(height) / double(kMinSamplesPerImage);
    qy = std::max(1, int(std::sqrt(r)));
    qx = std::max(1, int(r / qy));
    w = (width + qx - 1) / qx, h = (height + qy - 1) / qy;
  }
};

}  // namespace

int pilotSamplesPerImage(int width, int height) {
  const Cells cells(width, height);
  const size_t count = size_t(cells.w) * size_t(cells.h);
  return int((kMinSamplesPerImage + count - 1) / count);
}

PilotEstimates pilotEstimates(int width, int height, uint64_t seed, SamplerKind kind, int alternatives,
                              const PilotSample& sample, const std::vector<const PassData*>& passes) {
  const Cells cells(width, height);
  const int w = cells.w, h = cells.h, qx = cells.qx, qy = cells.qy;
  const size_t count = size_t(w) * size_t(h);
  const int n = pilotSamplesPerImage(width, height);  // samples per cell of each image
  if (!passes.empty() && passes.size() != size_t(2 * n))
    throw std::logic_error("pilotEstimates: " + std::to_string(passes.size()) + " passes for " +
                           std::to_string(2 * n) + " samples per cell");
  const double scale = 1.0 / n;
  std::array<Image, 2> images;
  for (Image& img : images) img.assign(count, {0.0, 0.0, 0.0});
  PilotEstimates out;
  std::vector<Image> excess(size_t(alternatives), Image(count, {0.0, 0.0, 0.0}));
  // Rows are traced in batches; each batch's splats and excess (per row and image) are then added
  // in row order, so the result does not depend on scheduling, and the batch's buffers are reused
  // by the next one (holding every row's at once cost more time in page faults than the samples).
  constexpr int kBatchRows = 16;
  std::array<std::array<SampleContext, 2>, kBatchRows> rows;
  using Excess = std::vector<std::vector<Splat>>;  // per alternative
  std::array<Excess, kBatchRows> rowExcess;
  for (Excess& e : rowExcess) e.resize(size_t(alternatives));
  const uint64_t pilotSeed = seed * 0x9E3779B97F4A7C15ull + 0x2545F4914F6CDD1Dull;
  for (int y0 = 0; y0 < h; y0 += kBatchRows) {
    const int y1 = std::min(h, y0 + kBatchRows);
    tbb::parallel_for(y0, y1, [&](int y) {
      const int py = std::min(y * qy + qy / 2, height - 1);
      const size_t r = size_t(y - y0);
      for (int image = 0; image < 2; ++image) rows[r][image].splats.clear();
      for (std::vector<Splat>& e : rowExcess[r]) e.clear();
      for (int x = 0; x < w; ++x) {
        const int px = std::min(x * qx + qx / 2, width - 1);
        for (int image = 0; image < 2; ++image)
          for (int j = 0; j < n; ++j) {
            const size_t i = size_t(y) * w + x;
            Sampler rng(kind, pilotSeed, uint64_t(py) * uint64_t(width) + uint64_t(px), uint32_t(image * n + j));
            if (!passes.empty()) rows[r][image].pass = passes[size_t(image * n + j)];
            add(images[image], i, sample(Vec2(float(px), float(py)), rng, rows[r][image], rowExcess[r]), scale);
          }
      }
    });
    for (int y = y0; y < y1; ++y) {
      const size_t r = size_t(y - y0);
      for (int image = 0; image < 2; ++image) addAt(images[image], w, h, qx, qy, rows[r][image].splats, scale);
      for (int a = 0; a < alternatives; ++a)  // per sample: over the 2n of each cell
        addAt(excess[size_t(a)], w, h, qx, qy, rowExcess[r][size_t(a)], 0.5 * scale);
    }
  }
  // Each slot's ray counter has added up over every batch it served.
  for (const auto& row : rows)
    for (const SampleContext& ctx : row) out.rays.closest += ctx.counter.closest, out.rays.shadow += ctx.counter.shadow;
  const Image mean = neighbourMean(images, w, h);
  std::vector<double> rel(count, 0.0);
  out.relExcess.assign(size_t(alternatives), 0.0);
  for (size_t i = 0; i < count; ++i)
    for (int c = 0; c < 3; ++c) {
      const double d = images[0][i][c] - images[1][i][c], m2 = mean[i][c] * mean[i][c] + 1e-2;
      rel[i] += n * 0.5 * d * d / m2;  // per sample: n × the mean's
      for (int a = 0; a < alternatives; ++a) out.relExcess[size_t(a)] += excess[size_t(a)][i][c] / m2 / double(count);
    }
  out.relVar = trimmedMean(std::move(rel));
  out.samples = 2 * size_t(n) * count;
  return out;
}

std::vector<Vec2> spreadPixels(int width, int height, size_t pixels) {
  const double aspect = double(width) / double(height);
  const int gx = std::clamp(int(std::lround(std::sqrt(double(pixels) * aspect))), 1, width);
  const int gy = int((pixels + size_t(gx) - 1) / size_t(gx));
  std::vector<Vec2> out(pixels);
  for (size_t j = 0; j < pixels; ++j) {
    const int cx = int(j % size_t(gx)), cy = int(j / size_t(gx));
    out[j] = Vec2(std::floor((float(cx) + 0.5f) * float(width) / float(gx)),
                  std::floor((float(cy) + 0.5f) * float(height) / float(gy)));
  }
  return out;
}

double relativeVarianceAtPixels(int width, int height, uint64_t seed, SamplerKind kind, int spp, size_t pixels,
                                const PilotSample& sample, RayCounter& rays) {
  const size_t all = size_t(width) * size_t(height);
  pixels = std::min(pixels, all);
  const std::vector<Vec2> at = spreadPixels(width, height, pixels);
  std::vector<double> rel(pixels, 0.0);
  std::vector<SampleContext> ctx(pixels);
  const uint64_t seeds[2] = {seed * 0xC2B2AE3D27D4EB4Full + 0x165667B19E3779F9ull,
                             seed * 0x94D049BB133111EBull + 0x27D4EB2F165667C5ull};
  tbb::parallel_for(size_t(0), pixels, [&](size_t j) {
    const Vec2 pixel = at[j];
    const size_t i = size_t(pixel.y) * size_t(width) + size_t(pixel.x);
    std::vector<std::vector<Splat>> excess;
    Image x(2, {0.0, 0.0, 0.0});  // the pixel in each image
    for (int image = 0; image < 2; ++image)
      for (int k = 0; k < spp; ++k) {
        Sampler rng(kind, seeds[image], uint64_t(i), uint32_t(k));
        add(x, size_t(image), sample(pixel, rng, ctx[j], excess), 1.0 / spp);
      }
    for (int c = 0; c < 3; ++c) {
      const double d = x[0][c] - x[1][c], m = 0.5 * (x[0][c] + x[1][c]);
      rel[j] += spp * 0.5 * d * d / (m * m + 1e-2);
    }
  });
  for (const SampleContext& c : ctx) rays.closest += c.counter.closest, rays.shadow += c.counter.shadow;
  return trimmedMean(std::move(rel));
}

RayCounter raysOfSamples(int width, int height, uint64_t seed, SamplerKind kind, size_t count, const PilotSample& sample) {
  const std::vector<Vec2> at = spreadPixels(width, height, std::min(count, size_t(width) * size_t(height)));
  std::vector<SampleContext> ctx(count);
  const uint64_t raySeed = seed * 0xD1B54A32D192ED03ull + 0x8CB92BA72F3D8DD7ull;
  tbb::parallel_for(size_t(0), count, [&](size_t j) {
    std::vector<std::vector<Splat>> excess;
    const Vec2 pixel = at[j % at.size()];
    Sampler rng(kind, raySeed, uint64_t(pixel.y) * uint64_t(width) + uint64_t(pixel.x), uint32_t(j));
    sample(pixel, rng, ctx[j], excess);
  });
  RayCounter rays;
  for (const SampleContext& c : ctx) rays.closest += c.counter.closest, rays.shadow += c.counter.shadow;
  return rays;
}

double raysPerSample(int width, int height, uint64_t seed, const PilotSample& sample, RayCounter& counter) {
  constexpr size_t kSamples = 1024;
  const RayCounter r = raysOfSamples(width, height, seed, SamplerKind::Independent, kSamples, sample);
  counter.closest += r.closest, counter.shadow += r.shadow;
  return double(r.closest + r.shadow) / double(kSamples);
}

}  // namespace kasha::bidir
