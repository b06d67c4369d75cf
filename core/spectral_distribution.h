#pragma once
// Importance sampling of wavelengths in proportion to a spectrum over a range. The density is
// exactly spectrum(λ) / ∫spectrum, because a piecewise-linear function is sampled segment by
// segment with the inverse of its quadratic CDF.
#include <vector>

#include "core/spectrum.h"

namespace kasha {

struct WavelengthSample {
  float lambda = 0.0f;
  float pdf = 0.0f;  // per nm
};

class SpectralDistribution {
 public:
  SpectralDistribution() = default;
  SpectralDistribution(const Spectrum& s, WavelengthRange range);

  WavelengthSample sample(float u) const;
  float pdf(float lambda) const;
  // ∫ spectrum over the range; 0 means nothing can be sampled.
  float integral() const { return total_; }
  const WavelengthRange& range() const { return range_; }

 private:
  std::vector<float> x_, y_, cdf_;  // knots restricted to the range; cdf_[i] = mass before knot i
  std::vector<uint32_t> guide_;     // guide_[k]: first knot with cdf_ > k/size·total (search start)
  Spectrum spectrum_;
  WavelengthRange range_;
  float total_ = 0.0f;
};

}  // namespace kasha
