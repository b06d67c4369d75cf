#pragma once
// Piecewise-constant densities over [0, 1] and [0, 1]² (pbrt-v4 §A.5: a marginal density over
// rows and a conditional density per row), sampled by inverting their CDFs. A cell's density is
// its weight over the mean weight; cells of zero weight are never sampled.
#include <algorithm>
#include <vector>

#include "core/math.h"

namespace kasha {

// The cell of n equal cells over [0, 1) holding t; t outside (or NaN) clamps to the first or
// last cell, without the undefined float-to-int conversion of an out-of-range value.
inline int cellIndex(float t, int n) {
  const float x = t * float(n);
  if (!(x > 0.0f)) return 0;
  return x < float(n) ? std::min(int(x), n - 1) : n - 1;
}

class Distribution1D {
 public:
  // Non-negative weights of n equal cells over [0, 1].
  explicit Distribution1D(std::vector<float> weights);
  struct Sample {
    float x = 0.0f;    // in [0, 1)
    float pdf = 0.0f;  // density per unit x
    size_t cell = 0;
  };
  Sample sample(float u) const;
  float pdf(size_t cell) const { return total_ > 0.0 ? float(w_[cell] * double(w_.size()) / total_) : 0.0f; }
  size_t size() const { return w_.size(); }
  double total() const { return total_; }  // Σ weights

 private:
  std::vector<float> w_;
  std::vector<double> cdf_;  // cdf_[i] = Σ_{j<i} w_j, size n + 1
  double total_ = 0.0;
};

class Distribution2D {
 public:
  // Row-major weights of width × height cells over [0, 1]² (u along a row, v down the rows).
  Distribution2D(const std::vector<float>& weights, int width, int height);
  struct Sample {
    Vec2 uv;
    float pdf = 0.0f;  // density per unit area of [0, 1]²
  };
  Sample sample(Vec2 u) const;
  float pdf(Vec2 uv) const;
  bool empty() const { return marginal_.total() <= 0.0; }

 private:
  int w_, h_;
  std::vector<Distribution1D> rows_;
  Distribution1D marginal_;
};

}  // namespace kasha
