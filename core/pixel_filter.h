#pragma once
// Pixel reconstruction filters as Mitsuba 3 parameterises them (Mitsuba 3 docs: rfilter box, tent,
// gaussian): separable, f(x, y) = g(x)·g(y) with x, y the offset in pixels from a pixel's centre,
//   box       g(x) = 1 on |x| < 1/2 (one pixel wide)
//   tent      g(x) = max(0, 1 − |x|/r), r = `radius` (default 1)
//   gaussian  g(x) = max(0, exp(−x²/2σ²) − exp(−r²/2σ²)), σ = `stddev` (default 0.5), r = 4σ
// Pixel j (centre c_j) measures I_j = ∫ f(x − c_j)·L(x) dx / ∫ f over the film x (pbrt-v4 §5.4.3,
// §8.8). Camera samples use filter importance sampling: pixel j's sample lies at c_j + an offset of
// density f/∫f, drawn exactly (inverse CDF per axis), so its weight f/p·(1/∫f) is 1 and it counts
// for pixel j alone. A light-tracing splat at film position x adds to every pixel j whose support
// holds x, weighted f(x − c_j)/∫f (splat()). The box filter reproduces pixel + uniform jitter and
// one splat per pixel exactly.
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "core/math.h"

namespace kasha {

enum class PixelFilterType { Box, Tent, Gaussian };

class PixelFilter {
 public:
  // The supports accepted (radius in pixels): a splat touches at most (2r + 1)² pixels, and 1/∫f
  // stays finite.
  static constexpr float kMinRadius = 1.0f / 64.0f, kMaxRadius = 16.0f;

  PixelFilter() = default;  // the box filter
  static PixelFilter tent(float radius);
  static PixelFilter gaussian(float stddev);

  PixelFilterType type() const { return type_; }
  const char* name() const;
  // The support's half-width in pixels (box 1/2, tent r, gaussian 4σ).
  float radius() const { return radius_; }
  float stddev() const { return stddev_; }  // gaussian only

  // g(x), unnormalised, as Mitsuba defines it.
  float profile(float x) const;
  // f(offset)/∫f: the density of a camera sample's offset from its pixel's centre, per pixel².
  float density(Vec2 offset) const { return profile(offset.x) * profile(offset.y) * invNorm2_; }

  // The film position (x right, y down, in pixels) of a camera sample of the pixel whose corner is
  // `pixel`, from two uniform numbers: pixel + u for the box, else the pixel's centre plus an
  // offset of density `density`, strictly inside the support.
  Vec2 filmPosition(Vec2 pixel, Vec2 u) const;
  // How far beyond the image's edges (pixels) camera samples land and splats count: r − 1/2.
  float filmMargin() const { return std::max(0.0f, radius_ - 0.5f); }
  // The density of camera samples at film position x relative to uniform over the w × h image,
  // Σ_j f(x − c_j)/∫f over its pixels j (the pixels are sampled equally often): 1 inside the image
  // for the box, 0 outside; its product with the camera's uniform density is the direction density
  // of camera rays, for MIS (docs/bdpt-mis.md).
  float coverage(Vec2 x, int w, int h) const;

  // Calls fn(px, py, weight) for every pixel of the w × h image whose support holds film position
  // x, weight f(x − c_j)/∫f. The box filter adds to the pixel holding x (clamped to the image),
  // with weight 1.
  template <class Fn>
  void splat(Vec2 x, int w, int h, Fn&& fn) const {
    if (type_ == PixelFilterType::Box) {
      // Clamped as floats: converting a huge float to int would be undefined behaviour.
      fn(int(std::clamp(x.x, 0.0f, float(w - 1))), int(std::clamp(x.y, 0.0f, float(h - 1))), 1.0f);
      return;
    }
    AxisWeights ax, ay;
    axisWeights(x.x, w, ax);
    axisWeights(x.y, h, ay);
    for (int j = 0; j < ay.count; ++j)
      for (int i = 0; i < ax.count; ++i)
        if (const float weight = ax.g[i] * ay.g[j] * invNorm2_; weight > 0.0f) fn(ax.first + i, ay.first + j, weight);
  }

 private:
  // The pixels along one axis whose support holds coordinate x, and g at their centres.
  struct AxisWeights {
    int first = 0, count = 0;
    float g[2 * int(kMaxRadius) + 2];
  };
  void axisWeights(float x, int pixels, AxisWeights& out) const;
  // ∫_{−r}^{x} g and its inverse (the offset of a camera sample along one axis from u ∈ [0, 1)).
  double cdf(double x) const;
  float sampleAxis(float u) const;

  PixelFilterType type_ = PixelFilterType::Box;
  float radius_ = 0.5f, stddev_ = 0.0f;
  float floor_ = 0.0f;         // gaussian: exp(−r²/2σ²), subtracted so that g reaches 0 at r
  double integral_ = 1.0;      // ∫ g over the support
  float invNorm2_ = 1.0f;      // 1/∫f = 1/(∫g)²
  std::vector<float> inverseCdf_;  // gaussian: offsets at u = k/n, k = 0 … n, to start Newton's method
};

}  // namespace kasha
