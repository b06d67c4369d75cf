#pragma once
// Helpers shared by the material tests.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "core/rng.h"
#include "core/sampling.h"

namespace kasha::test {

inline Vec3 dirFromCosPhi(float cosTheta, float phi) {
  const float s = std::sqrt(std::max(0.0f, 1.0f - cosTheta * cosTheta));
  return Vec3(s * std::cos(phi), s * std::sin(phi), cosTheta);
}

// A uniform direction away from the tangent plane.
inline Vec3 randomDirection(Rng& rng) {
  for (;;) {
    const Vec3 w = sampleUniformSphere(Vec2(rng.uniform(), rng.uniform()));
    if (std::abs(w.z) > 1e-3f) return w;
  }
}

// |a − b| ≤ rel·max(|a|, |b|) + abs
inline ::testing::AssertionResult close(double a, double b, double rel, double abs = 0.0) {
  if (std::abs(a - b) <= rel * std::max(std::abs(a), std::abs(b)) + abs) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << a << " vs " << b << " (rel " << rel << ", abs " << abs << ")";
}

}  // namespace kasha::test
