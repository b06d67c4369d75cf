#pragma once
// Helpers shared by the material tests.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "core/rng.h"
#include "core/sampling.h"
#include "materials/material.h"

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

// The Bsdf a material builds at a hit whose local frame is the world frame (so local directions
// pass through unchanged), for a path at wavelength `lambda`, at texture coordinates uv.
inline Bsdf localBsdf(const Material& m, float lambda = 550.0f, Vec2 uv = Vec2(0.0f)) {
  const Frame world{Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)};
  return m.bsdf(HitContext{uv, world, world, {&lambda, 1}});
}

// |a − b| ≤ rel·max(|a|, |b|) + abs
inline ::testing::AssertionResult close(double a, double b, double rel, double abs = 0.0) {
  if (std::abs(a - b) <= rel * std::max(std::abs(a), std::abs(b)) + abs) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << a << " vs " << b << " (rel " << rel << ", abs " << abs << ")";
}

}  // namespace kasha::test
