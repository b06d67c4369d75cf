#pragma once
// A density over wavelength that is a weighted sum of spectral distributions,
//   p(λ) = Σ_k c_k·p_k(λ),  Σ_k c_k = 1,
// sampled by choosing k with probability c_k and then λ from p_k. This is one-sample MIS with the
// balance heuristic (Veach97 §9.2.4), whose estimator f/(Σ c_k p_k) is the mixture's.
#include <functional>
#include <memory>
#include <vector>

#include "core/spectral_distribution.h"

namespace kasha {

class WavelengthDensity {
 public:
  // weight > 0; the weights are normalised to sum to one. A distribution with zero integral is
  // rejected (std::invalid_argument), since it cannot be sampled.
  void add(std::shared_ptr<const SpectralDistribution> d, float weight);
  // Adds every component of `other`, its weights scaled by `weight` (mixtures stay flat).
  void add(const WavelengthDensity& other, float weight);

  WavelengthSample sample(float u) const;
  float pdf(float lambda) const;
  bool empty() const { return d_.empty(); }
  size_t size() const { return d_.size(); }
  float weight(size_t k) const { return w_[k] / total_; }

  // The first wavelength of `range` (scanned every 0.25 nm) where target(λ) > 0 but p(λ) = 0, or
  // a negative value if there is none: a density must not miss any wavelength where the
  // integrand can be non-zero, or the estimate is biased.
  float firstUncovered(const std::function<float(float)>& target, WavelengthRange range) const;

 private:
  std::vector<std::shared_ptr<const SpectralDistribution>> d_;
  std::vector<float> w_;
  float total_ = 0.0f;
};

}  // namespace kasha
