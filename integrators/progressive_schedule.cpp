#include "integrators/progressive_schedule.h"

#include <cmath>

namespace kasha {

float progressiveRadiusSquared(float r1, float alpha, int iteration) {
  const double i = iteration;
  return float(double(r1) * r1 * std::exp(std::lgamma(i + alpha) - std::lgamma(1.0 + alpha) - std::lgamma(i + 1.0)));
}

float wavelengthKernel(float x, float h) {
  const float t = x / h;
  return t * t < 1.0f ? 0.75f * (1.0f - t * t) / h : 0.0f;
}

}  // namespace kasha
