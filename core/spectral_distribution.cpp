#include "core/spectral_distribution.h"

#include <algorithm>
#include <cmath>

namespace kasha {

SpectralDistribution::SpectralDistribution(const Spectrum& s, WavelengthRange range)
    : spectrum_(s), range_(range) {
  // Knots inside the range, with the range ends; at a step keep both sides (left limit, right value).
  x_.push_back(range.min);
  y_.push_back(s(range.min));
  const auto& kx = s.lambdas();
  const auto& ky = s.values();
  for (size_t i = 0; i < kx.size(); ++i) {
    if (kx[i] <= range.min || kx[i] >= range.max) continue;
    x_.push_back(kx[i]);
    y_.push_back(std::max(0.0f, ky[i]));
  }
  x_.push_back(range.max);
  {
    float endY = s(range.max);
    auto hit = std::lower_bound(kx.begin(), kx.end(), range.max);
    if (hit != kx.end() && *hit == range.max) endY = ky[size_t(hit - kx.begin())];
    y_.push_back(std::max(0.0f, endY));
  }
  y_.front() = std::max(0.0f, y_.front());
  cdf_.assign(x_.size(), 0.0f);
  double acc = 0.0;
  for (size_t i = 0; i + 1 < x_.size(); ++i) {
    acc += 0.5 * double(y_[i] + y_[i + 1]) * double(x_[i + 1] - x_[i]);
    cdf_[i + 1] = float(acc);
  }
  total_ = float(acc);
  guide_.resize(std::min<size_t>(256, x_.size()));
  for (size_t k = 0, i = 0; k < guide_.size(); ++k) {
    const float target = total_ * float(k) / float(guide_.size());
    while (i + 1 < cdf_.size() && cdf_[i + 1] <= target) ++i;
    guide_[k] = uint32_t(i);
  }
}

WavelengthSample SpectralDistribution::sample(float u) const {
  if (total_ <= 0.0f) return {};
  const float target = u * total_;
  // segment i: cdf_[i] <= target < cdf_[i+1], skipping zero-width and zero-mass segments
  size_t i = guide_[std::min(size_t(u * float(guide_.size())), guide_.size() - 1)];
  while (i + 2 < x_.size() && cdf_[i + 1] <= target) ++i;
  while (i + 1 < x_.size() - 1 && cdf_[i + 1] <= cdf_[i]) ++i;
  const float y0 = y_[i], y1 = y_[i + 1], w = x_[i + 1] - x_[i];
  const float mass = cdf_[i + 1] - cdf_[i];
  const float v = std::clamp((target - cdf_[i]) / std::max(mass, 1e-30f), 0.0f, 1.0f);
  // Solve y0·t + (y1−y0)·t²/2 = v·(y0+y1)/2 for t in [0,1], in a form stable for y1 ≈ y0.
  const float a = 0.5f * (y0 + y1);
  const float disc = std::max(0.0f, y0 * y0 + 2.0f * (y1 - y0) * v * a);
  const float denom = y0 + std::sqrt(disc);
  const float t = denom > 0.0f ? std::clamp(2.0f * v * a / denom, 0.0f, 1.0f) : v;
  float lambda = std::min(x_[i] + t * w, range_.max);
  float p = pdf(lambda);
  if (p <= 0.0f) {
    // u at the ends of its float grid can land exactly on a segment end where the density is zero
    // (a zero-valued knot, or the far side of a step): step one ulp into the segment.
    lambda = std::min(std::max(lambda, std::nextafter(x_[i], x_[i + 1])), std::nextafter(x_[i + 1], x_[i]));
    p = pdf(lambda);
  }
  return {lambda, p};
}

float SpectralDistribution::pdf(float lambda) const {
  if (total_ <= 0.0f || lambda < range_.min || lambda > range_.max) return 0.0f;
  return std::max(0.0f, spectrum_(lambda)) / total_;
}

}  // namespace kasha
