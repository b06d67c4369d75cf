#include "core/pixel_filter.h"

namespace kasha {
namespace {

// Offsets tabulated for the Gaussian's inverse CDF: Newton's method starts between two of them.
constexpr int kInverseCdfNodes = 64;

}  // namespace

PixelFilter PixelFilter::tent(float radius) {
  PixelFilter f;
  f.type_ = PixelFilterType::Tent;
  f.radius_ = radius;
  f.integral_ = radius;  // ∫ max(0, 1 − |x|/r) dx = r
  f.invNorm2_ = float(1.0 / (f.integral_ * f.integral_));
  return f;
}

PixelFilter PixelFilter::gaussian(float stddev) {
  PixelFilter f;
  f.type_ = PixelFilterType::Gaussian;
  f.stddev_ = stddev;
  f.radius_ = 4.0f * stddev;  // Mitsuba 3 docs: gaussian, cut off after 4 standard deviations
  const double s = stddev, r = f.radius_;
  f.floor_ = float(std::exp(-r * r / (2.0 * s * s)));
  f.integral_ = f.cdf(r);
  f.invNorm2_ = float(1.0 / (f.integral_ * f.integral_));
  // The inverse CDF at u = k/n by bisection (the CDF increases strictly on (−r, r)).
  f.inverseCdf_.resize(kInverseCdfNodes + 1);
  f.inverseCdf_.front() = -f.radius_;
  f.inverseCdf_.back() = f.radius_;
  for (int k = 1; k < kInverseCdfNodes; ++k) {
    const double target = f.integral_ * k / kInverseCdfNodes;
    double lo = -r, hi = r;
    for (int i = 0; i < 64; ++i) (f.cdf(0.5 * (lo + hi)) < target ? lo : hi) = 0.5 * (lo + hi);
    f.inverseCdf_[size_t(k)] = float(0.5 * (lo + hi));
  }
  return f;
}

const char* PixelFilter::name() const {
  switch (type_) {
    case PixelFilterType::Box: return "box";
    case PixelFilterType::Tent: return "tent";
    case PixelFilterType::Gaussian: return "gaussian";
  }
  return "";
}

float PixelFilter::profile(float x) const {
  const double a = std::abs(double(x));
  if (!(a < radius_)) return 0.0f;
  switch (type_) {
    case PixelFilterType::Box: return 1.0f;
    case PixelFilterType::Tent: return float(1.0 - a / radius_);
    case PixelFilterType::Gaussian: {
      const double s = stddev_;
      return float(std::max(0.0, std::exp(-a * a / (2.0 * s * s)) - double(floor_)));
    }
  }
  return 0.0f;
}

double PixelFilter::cdf(double x) const {
  const double r = radius_;
  x = std::clamp(x, -r, r);
  switch (type_) {
    case PixelFilterType::Box: return x + 0.5;
    case PixelFilterType::Tent: return x <= 0.0 ? (x + r) * (x + r) / (2.0 * r) : r - (r - x) * (r - x) / (2.0 * r);
    case PixelFilterType::Gaussian: {
      // ∫_{−r}^{x} exp(−t²/2σ²) dt = σ·√(π/2)·(erf(x/(σ√2)) + erf(r/(σ√2))), less the floor's share.
      const double s = stddev_, k = 1.0 / (s * std::sqrt(2.0));
      return s * std::sqrt(0.5 * kPi) * (std::erf(x * k) + std::erf(r * k)) - double(floor_) * (x + r);
    }
  }
  return 0.0;
}

float PixelFilter::sampleAxis(float u) const {
  const double r = radius_;
  double x = 0.0;
  if (type_ == PixelFilterType::Tent) {
    // The tent's CDF inverted on each side of its peak.
    x = u < 0.5f ? -r + r * std::sqrt(2.0 * u) : r - r * std::sqrt(2.0 * (1.0 - u));
  } else {
    // Newton's method on cdf(x) = u·∫g from the tabulated inverse, kept inside the bracket of the two
    // nodes around u (bisection where a step leaves it).
    const double t = double(u) * kInverseCdfNodes;
    const int k = std::min(int(t), kInverseCdfNodes - 1);
    double lo = inverseCdf_[size_t(k)], hi = inverseCdf_[size_t(k) + 1];
    const double target = double(u) * integral_;
    x = lo + (hi - lo) * (t - k);
    for (int i = 0; i < 32; ++i) {
      const double excess = cdf(x) - target;
      (excess < 0.0 ? lo : hi) = x;
      const double g = profile(float(x));
      double next = g > 0.0 ? x - excess / g : 0.5 * (lo + hi);
      if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
      const bool converged = std::abs(next - x) < 1e-7 * r;
      x = next;
      if (converged) break;
    }
  }
  // Strictly inside the support, where the density is positive.
  const float inside = std::nextafter(radius_, 0.0f);
  return std::clamp(float(x), -inside, inside);
}

Vec2 PixelFilter::filmPosition(Vec2 pixel, Vec2 u) const {
  if (type_ == PixelFilterType::Box) return pixel + u;
  return pixel + Vec2(0.5f) + Vec2(sampleAxis(u.x), sampleAxis(u.y));
}

void PixelFilter::axisWeights(float x, int pixels, AxisWeights& out) const {
  // Pixels i with |x − (i + 1/2)| < r, clamped to the image (as floats: x may be far outside).
  const float first = std::clamp(std::floor(x - 0.5f - radius_) + 1.0f, 0.0f, float(pixels));
  const float last = std::clamp(std::ceil(x - 0.5f + radius_) - 1.0f, -1.0f, float(pixels - 1));
  out.first = int(first);
  out.count = std::clamp(int(last) - out.first + 1, 0, int(std::size(out.g)));
  for (int i = 0; i < out.count; ++i) out.g[i] = profile(x - (float(out.first + i) + 0.5f));
}

float PixelFilter::coverage(Vec2 x, int w, int h) const {
  if (type_ == PixelFilterType::Box) return x.x >= 0.0f && x.x <= float(w) && x.y >= 0.0f && x.y <= float(h) ? 1.0f : 0.0f;
  AxisWeights ax, ay;
  axisWeights(x.x, w, ax);
  axisWeights(x.y, h, ay);
  float sx = 0.0f, sy = 0.0f;
  for (int i = 0; i < ax.count; ++i) sx += ax.g[i];
  for (int j = 0; j < ay.count; ++j) sy += ay.g[j];
  return sx * sy * invNorm2_;
}

}  // namespace kasha
