#include "core/spectrum.h"

#include "core/math.h"

#include <algorithm>
#include <cassert>
#include <cmath>

namespace kasha {

Spectrum::Spectrum(std::vector<float> x, std::vector<float> y) : x_(std::move(x)), y_(std::move(y)) {
  assert(!x_.empty() && x_.size() == y_.size());
  minimum_ = *std::min_element(y_.begin(), y_.end());
  size_t i0 = 0, i1 = x_.size() - 1;
  if (i1 >= 1 && x_[0] == x_[1]) i0 = 1;
  if (i1 >= 1 && x_[i1] == x_[i1 - 1]) --i1;
  // The longest run of equally spaced knots from i0 (a table's odd last knot, as in 400, 500, 600,
  // 700, 700.01, leaves the rest of it on the O(1) path).
  if (i1 >= i0 + 1 && x_[i0 + 1] > x_[i0]) {
    const float step = x_[i0 + 1] - x_[i0];
    size_t end = i0 + 1;
    while (end < i1 && std::abs((x_[end + 1] - x_[i0]) - step * float(end + 1 - i0)) <= 1e-4f * step) ++end;
    uniformStep_ = step, i0_ = i0, i1_ = end;
  }
}

Spectrum Spectrum::constant(float value) { return Spectrum({0.0f}, {value}); }

Spectrum Spectrum::piecewiseLinear(std::vector<float> lambdas, std::vector<float> values) {
  return Spectrum(std::move(lambdas), std::move(values));
}

Spectrum Spectrum::box(float lo, float hi, float value) {
  return Spectrum({lo, lo, hi, hi}, {0.0f, value, value, 0.0f});
}

Spectrum Spectrum::gaussian(float centre, float fwhm, float peak) {
  const float sigma = fwhm / (2.0f * std::sqrt(2.0f * std::log(2.0f)));
  const int n = 600;  // FWHM/100 steps over ±3 FWHM
  std::vector<float> x(n + 1), y(n + 1);
  for (int i = 0; i <= n; ++i) {
    const double l = centre - 3.0 * fwhm + 6.0 * fwhm * i / n;
    x[i] = float(l);
    y[i] = (i == 0 || i == n) ? 0.0f : float(peak * std::exp(-0.5 * sqr(float((l - centre) / sigma))));
  }
  return Spectrum(std::move(x), std::move(y));
}

Spectrum Spectrum::blackbody(float kelvin) {
  // Planck: B(λ, T) = 2hc² / λ⁵ / (exp(hc / (λ k T)) − 1)
  const double h = 6.62607015e-34, c = 2.99792458e8, kb = 1.380649e-23;
  auto planck = [&](double nm) {
    const double l = nm * 1e-9;
    return 2.0 * h * c * c / (std::pow(l, 5) * (std::exp(h * c / (l * kb * kelvin)) - 1.0));
  };
  std::vector<float> x, y;
  double peak = 0.0;
  for (int nm = 200; nm <= 2000; ++nm) {
    x.push_back(float(nm));
    y.push_back(float(planck(nm)));
    if (nm >= 300 && nm <= 830) peak = std::max(peak, planck(nm));
  }
  for (float& v : y) v = float(v / peak);
  return Spectrum(std::move(x), std::move(y));
}

float Spectrum::evaluateByKnotSearch(float lambda) const {
  if (lambda <= x_.front()) return lambda < x_.front() ? y_.front() : y_[std::upper_bound(x_.begin(), x_.end(), lambda) - x_.begin() - 1];
  if (lambda >= x_.back()) return y_.back();
  // segment [x_i, x_{i+1}) holding lambda
  const size_t i = size_t(std::upper_bound(x_.begin(), x_.end(), lambda) - x_.begin()) - 1;
  const float t = (lambda - x_[i]) / (x_[i + 1] - x_[i]);
  return y_[i] + t * (y_[i + 1] - y_[i]);
}

float Spectrum::leftLimit(float lambda) const {
  auto hit = std::lower_bound(x_.begin(), x_.end(), lambda);
  if (hit != x_.end() && *hit == lambda) return y_[size_t(hit - x_.begin())];
  return (*this)(lambda);
}

Spectrum Spectrum::weightedSum(const std::vector<std::pair<float, const Spectrum*>>& terms) {
  std::vector<float> knots;
  for (const auto& [w, s] : terms) knots.insert(knots.end(), s->x_.begin(), s->x_.end());
  std::sort(knots.begin(), knots.end());
  knots.erase(std::unique(knots.begin(), knots.end()), knots.end());
  if (knots.empty()) return constant(0.0f);
  std::vector<float> x, y;
  for (float k : knots) {
    float left = 0.0f, right = 0.0f;
    for (const auto& [w, s] : terms) {
      left += w * s->leftLimit(k);
      right += w * (*s)(k);
    }
    if (left != right) {
      x.push_back(k);
      y.push_back(left);
    }
    x.push_back(k);
    y.push_back(right);
  }
  return Spectrum(std::move(x), std::move(y));
}

float Spectrum::integral(float lo, float hi) const {
  if (hi <= lo) return 0.0f;
  // Knots strictly inside (lo, hi) plus the ends; the function is linear between them.
  double sum = 0.0;
  float prevX = lo, prevY = (*this)(lo);
  auto it = std::upper_bound(x_.begin(), x_.end(), lo);
  for (; it != x_.end() && *it < hi; ++it) {
    const size_t i = size_t(it - x_.begin());
    // at a step, (*this)(x) is the right value; the left limit is y_[i]
    sum += 0.5 * double(prevY + y_[i]) * double(x_[i] - prevX);
    prevX = x_[i];
    prevY = (*this)(x_[i]);
  }
  float endY = (*this)(hi);
  // left limit at hi if hi is a step
  auto hit = std::lower_bound(x_.begin(), x_.end(), hi);
  if (hit != x_.end() && *hit == hi) endY = y_[size_t(hit - x_.begin())];
  sum += 0.5 * double(prevY + endY) * double(hi - prevX);
  return float(sum);
}

float Spectrum::maxValue(float lo, float hi) const {
  float m = std::max((*this)(lo), (*this)(hi));
  for (size_t i = 0; i < x_.size(); ++i)
    if (x_[i] >= lo && x_[i] <= hi) m = std::max(m, y_[i]);
  return m;
}

float Spectrum::minValue(float lo, float hi) const {
  float m = std::min((*this)(lo), (*this)(hi));
  for (size_t i = 0; i < x_.size(); ++i)
    if (x_[i] >= lo && x_[i] <= hi) m = std::min(m, y_[i]);
  return m;
}

Spectrum Spectrum::scaled(float s) const {
  Spectrum r = *this;
  for (float& v : r.y_) v *= s;
  return r;
}

Spectrum Spectrum::zeroOutside() const {
  std::vector<float> x, y;
  x.push_back(x_.front());
  y.push_back(0.0f);
  x.insert(x.end(), x_.begin(), x_.end());
  y.insert(y.end(), y_.begin(), y_.end());
  x.push_back(x_.back());
  y.push_back(0.0f);
  return Spectrum(std::move(x), std::move(y));
}

}  // namespace kasha
