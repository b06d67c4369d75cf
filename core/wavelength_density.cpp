#include "core/wavelength_density.h"

#include <algorithm>
#include <stdexcept>

namespace kasha {

void WavelengthDensity::add(std::shared_ptr<const SpectralDistribution> d, float weight) {
  if (!(weight > 0.0f)) throw std::invalid_argument("wavelength density: component weight must be positive");
  if (!(d->integral() > 0.0f)) throw std::invalid_argument("wavelength density: component is zero over the range");
  d_.push_back(std::move(d));
  w_.push_back(weight);
  total_ += weight;
}

void WavelengthDensity::add(const WavelengthDensity& other, float weight) {
  for (size_t k = 0; k < other.d_.size(); ++k) add(other.d_[k], weight * other.weight(k));
}

WavelengthSample WavelengthDensity::sample(float u) const {
  if (d_.empty()) return {};
  // Choose component k with probability c_k, then reuse u rescaled within its interval.
  float target = u * total_, acc = 0.0f;
  size_t k = 0;
  for (; k + 1 < d_.size(); ++k) {
    if (target < acc + w_[k]) break;
    acc += w_[k];
  }
  const float v = std::clamp((target - acc) / w_[k], 0.0f, 0x1.fffffep-1f);
  const WavelengthSample s = d_[k]->sample(v);
  if (s.pdf <= 0.0f) return {};
  if (d_.size() == 1) return s;  // pdf() of one component is its own (below)
  return {s.lambda, pdf(s.lambda)};
}

float WavelengthDensity::pdf(float lambda) const {
  if (d_.size() == 1) return d_[0]->pdf(lambda);  // w·p/w, without its rounding
  float p = 0.0f;
  for (size_t k = 0; k < d_.size(); ++k) p += w_[k] * d_[k]->pdf(lambda);
  return p / total_;
}

float WavelengthDensity::firstUncovered(const std::function<float(float)>& target, WavelengthRange range) const {
  const int n = int((range.max - range.min) * 4.0f);
  for (int i = 0; i <= n; ++i) {
    const float l = std::min(range.min + 0.25f * float(i), range.max);
    if (target(l) > 0.0f && !(pdf(l) > 0.0f)) return l;
  }
  return -1.0f;
}

}  // namespace kasha
