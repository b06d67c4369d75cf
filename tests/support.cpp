#include "tests/support.h"

#include <algorithm>
#include <cmath>

namespace kasha::test {

BatchStats batchStats(const std::vector<double>& b) {
  BatchStats s;
  const double n = double(b.size());
  for (double v : b) s.mean += v / n;
  double var = 0.0;
  for (double v : b) var += (v - s.mean) * (v - s.mean) / (n - 1.0);
  s.stderr_ = std::sqrt(var / n);
  return s;
}

namespace {

// Regularised upper incomplete gamma Q(a, x) by series / continued fraction (Numerical Recipes §6.2).
double gammaQ(double a, double x) {
  if (x <= 0.0) return 1.0;
  const double gln = std::lgamma(a);
  if (x < a + 1.0) {
    double ap = a, sum = 1.0 / a, del = sum;
    for (int n = 0; n < 1000; ++n) {
      ap += 1.0;
      del *= x / ap;
      sum += del;
      if (std::abs(del) < std::abs(sum) * 1e-14) break;
    }
    return 1.0 - sum * std::exp(-x + a * std::log(x) - gln);
  }
  double b = x + 1.0 - a, c = 1.0 / 1e-300, d = 1.0 / b, h = d;
  for (int i = 1; i < 1000; ++i) {
    const double an = -i * (i - a);
    b += 2.0;
    d = an * d + b;
    if (std::abs(d) < 1e-300) d = 1e-300;
    c = b + an / c;
    if (std::abs(c) < 1e-300) c = 1e-300;
    d = 1.0 / d;
    const double del = d * c;
    h *= del;
    if (std::abs(del - 1.0) < 1e-14) break;
  }
  return std::exp(-x + a * std::log(x) - gln) * h;
}

}  // namespace

double chi2PValue(const std::vector<double>& observed, const std::vector<double>& expected) {
  // Sort cells by expected count and pool the small ones until the pool reaches 5.
  std::vector<size_t> idx(expected.size());
  for (size_t i = 0; i < idx.size(); ++i) idx[i] = i;
  std::sort(idx.begin(), idx.end(), [&](size_t a, size_t b) { return expected[a] < expected[b]; });
  double chi2 = 0.0, poolObs = 0.0, poolExp = 0.0;
  int dof = 0;
  for (size_t k : idx) {
    if (expected[k] == 0.0) {
      if (observed[k] > 0.0) return 0.0;  // a sample where the density is zero
      continue;
    }
    if (expected[k] < 5.0 || poolExp > 0.0) {
      poolObs += observed[k];
      poolExp += expected[k];
      if (poolExp >= 5.0) {
        chi2 += (poolObs - poolExp) * (poolObs - poolExp) / poolExp;
        ++dof;
        poolObs = poolExp = 0.0;
      }
      continue;
    }
    chi2 += (observed[k] - expected[k]) * (observed[k] - expected[k]) / expected[k];
    ++dof;
  }
  if (poolExp > 0.0) {
    chi2 += (poolObs - poolExp) * (poolObs - poolExp) / poolExp;
    ++dof;
  }
  if (dof <= 1) return 1.0;
  return gammaQ(0.5 * (dof - 1), 0.5 * chi2);
}

}  // namespace kasha::test
