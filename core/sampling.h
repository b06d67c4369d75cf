#pragma once
// Warps from the unit square to directions and points, with their densities.
#include "core/math.h"

namespace kasha {

// Shirley–Chiu concentric map of [0,1)² to the unit disk.
inline Vec2 sampleConcentricDisk(Vec2 u) {
  const Vec2 o = 2.0f * u - Vec2(1.0f);
  if (o.x == 0.0f && o.y == 0.0f) return Vec2(0.0f);
  float r, theta;
  if (std::abs(o.x) > std::abs(o.y)) {
    r = o.x;
    theta = (kPi / 4.0f) * (o.y / o.x);
  } else {
    r = o.y;
    theta = kPi / 2.0f - (kPi / 4.0f) * (o.x / o.y);
  }
  return r * Vec2(std::cos(theta), std::sin(theta));
}

// Cosine-weighted hemisphere around +z (Malley's method); density cosθ/π per steradian.
inline Vec3 sampleCosineHemisphere(Vec2 u) {
  const Vec2 d = sampleConcentricDisk(u);
  const float z = std::sqrt(std::max(0.0f, 1.0f - d.x * d.x - d.y * d.y));
  return Vec3(d.x, d.y, z);
}
inline float cosineHemispherePdf(float cosTheta) { return cosTheta > 0.0f ? cosTheta * kInvPi : 0.0f; }

// Uniform direction on the unit sphere; density 1/(4π).
inline Vec3 sampleUniformSphere(Vec2 u) {
  const float z = 1.0f - 2.0f * u.x;
  const float r = std::sqrt(std::max(0.0f, 1.0f - z * z));
  const float phi = 2.0f * kPi * u.y;
  return Vec3(r * std::cos(phi), r * std::sin(phi), z);
}
inline constexpr float kUniformSpherePdf = 1.0f / (4.0f * kPi);

// Uniform direction in the cone of half-angle acos(cosMax) around +z; density 1/(2π(1-cosMax)).
inline Vec3 sampleUniformCone(Vec2 u, float cosMax) {
  const float z = 1.0f - u.x * (1.0f - cosMax);
  const float r = std::sqrt(std::max(0.0f, 1.0f - z * z));
  const float phi = 2.0f * kPi * u.y;
  return Vec3(r * std::cos(phi), r * std::sin(phi), z);
}

// Uniform barycentrics on a triangle (Heitz 2019, "A low-distortion map between triangle and square").
inline Vec2 sampleUniformTriangle(Vec2 u) {
  float b0, b1;
  if (u.x < u.y) {
    b0 = u.x / 2.0f;
    b1 = u.y - b0;
  } else {
    b1 = u.y / 2.0f;
    b0 = u.x - b1;
  }
  return Vec2(b0, b1);
}

// Veach's power heuristic with β = 2 for two strategies.
inline float powerHeuristic(float pdfA, float pdfB) {
  const float a = pdfA * pdfA, b = pdfB * pdfB;
  return a + b > 0.0f ? a / (a + b) : 0.0f;
}

}  // namespace kasha
