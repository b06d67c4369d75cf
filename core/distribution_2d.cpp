#include "core/distribution_2d.h"

#include <algorithm>

namespace kasha {

Distribution1D::Distribution1D(std::vector<float> weights) : w_(std::move(weights)), cdf_(w_.size() + 1, 0.0) {
  for (size_t i = 0; i < w_.size(); ++i) cdf_[i + 1] = cdf_[i] + double(w_[i]);
  total_ = cdf_.back();
}

Distribution1D::Sample Distribution1D::sample(float u) const {
  if (!(total_ > 0.0)) return {};
  const double target = double(u) * total_;
  // The last cell whose CDF start is ≤ target, skipping cells of zero weight.
  size_t i = size_t(std::upper_bound(cdf_.begin(), cdf_.end(), target) - cdf_.begin());
  i = std::min(i == 0 ? 0 : i - 1, w_.size() - 1);
  while (w_[i] <= 0.0f && i + 1 < w_.size()) ++i;
  while (w_[i] <= 0.0f && i > 0) --i;
  const double within = std::clamp((target - cdf_[i]) / double(w_[i]), 0.0, 1.0);
  const float x = std::min(float((double(i) + within) / double(w_.size())), 0x1.fffffep-1f);
  return {x, pdf(i), i};
}

namespace {
std::vector<float> rowSums(const std::vector<float>& w, int width, int height) {
  std::vector<float> sums(static_cast<size_t>(height), 0.0f);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) sums[size_t(y)] += w[size_t(y) * size_t(width) + size_t(x)];
  return sums;
}
}  // namespace

Distribution2D::Distribution2D(const std::vector<float>& weights, int width, int height)
    : w_(width), h_(height), marginal_(rowSums(weights, width, height)) {
  rows_.reserve(size_t(height));
  for (int y = 0; y < height; ++y)
    rows_.emplace_back(std::vector<float>(weights.begin() + ptrdiff_t(y) * width, weights.begin() + ptrdiff_t(y + 1) * width));
}

Distribution2D::Sample Distribution2D::sample(Vec2 u) const {
  const Distribution1D::Sample v = marginal_.sample(u.y);
  if (!(v.pdf > 0.0f)) return {};
  const Distribution1D::Sample x = rows_[v.cell].sample(u.x);
  return {Vec2(x.x, v.x), v.pdf * x.pdf};
}

float Distribution2D::pdf(Vec2 uv) const {
  const size_t y = size_t(cellIndex(uv.y, h_)), x = size_t(cellIndex(uv.x, w_));
  return marginal_.pdf(y) * rows_[y].pdf(x);
}

}  // namespace kasha
