#include "integrators/progressive_schedule.h"

#include <algorithm>
#include <cmath>

namespace kasha {

namespace {

// ln (r_i/r_1)^d = ln Γ(i + α) − ln Γ(1 + α) − ln Γ(i + 1), whatever the dimension d.
double logVolumeShrink(float alpha, int iteration) {
  const double i = iteration;
  return std::lgamma(i + alpha) - std::lgamma(1.0 + alpha) - std::lgamma(i + 1.0);
}

}  // namespace

float progressiveRadius(float r1, float alpha, int iteration, int dimension) {
  return float(double(r1) * std::exp(logVolumeShrink(alpha, iteration) / dimension));
}

float progressiveRadiusSquared(float r1, float alpha, int iteration) {
  return float(double(r1) * r1 * std::exp(logVolumeShrink(alpha, iteration)));
}

float wavelengthKernel(float x, float h) {
  const float t = x / h;
  return t * t < 1.0f ? 0.75f * (1.0f - t * t) / h : 0.0f;
}

float wavelengthKernelMass(float lo, float hi, float h) {
  // The kernel's distribution function on u = x/h: 1/2 + 3u/4 − u³/4 on [−1, 1].
  auto cdf = [](float u) {
    u = std::clamp(u, -1.0f, 1.0f);
    return 0.5f + 0.75f * u - 0.25f * u * u * u;
  };
  return cdf(hi / h) - cdf(lo / h);
}

}  // namespace kasha
