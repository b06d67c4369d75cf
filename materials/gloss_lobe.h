#pragma once
// The white near-specular gloss peak of Zhdanov's three-part BDF (Zhdanov et al. 2019, §3: "a
// sharp near-specular peak ... not fluorescent"), modelled as the energy-conserving modified Phong
// lobe of Lafortune & Willems (1994):
//   f_g(ω_i, ω_o) = ρ_g·(n + 2)/(2π)·cos^n α,   cos α = ⟨ω_o, mirror(ω_i)⟩ = ⟨ω_i, mirror(ω_o)⟩,
// zero for cos α ≤ 0 and across the surface. Symmetric in ω_i and ω_o (reciprocal); its albedo
// ∫ f_g cos θ_o dω_o is at most ρ_g (equal at normal incidence). Sampled about the mirror
// direction of the known side with density (n + 1)/(2π)·cos^n α, which is also symmetric; samples
// below the surface are rejected (the density then integrates to less than 1).
#include <cmath>
#include <optional>

#include "core/sampling.h"
#include "materials/diffuse_lobe.h"
#include "materials/specular_lobe.h"

namespace kasha::gloss {

inline float cosAlpha(const Vec3& a, const Vec3& b) {
  return diffuse::sameSide(a, b) ? glm::dot(specular::reflect(a), b) : 0.0f;
}

// f_g / ρ_g
inline float value(const Vec3& wi, const Vec3& wo, float exponent) {
  const float c = cosAlpha(wi, wo);
  return c > 0.0f ? (exponent + 2.0f) * (0.5f * kInvPi) * std::pow(c, exponent) : 0.0f;
}

inline float pdf(const Vec3& wKnown, const Vec3& wSampled, float exponent) {
  const float c = cosAlpha(wKnown, wSampled);
  return c > 0.0f ? (exponent + 1.0f) * (0.5f * kInvPi) * std::pow(c, exponent) : 0.0f;
}

inline std::optional<DirectionSample> sample(const Vec3& wKnown, Vec2 u, float exponent) {
  if (wKnown.z == 0.0f) return std::nullopt;
  // cos α = u^(1/(n+1)) has density (n+1)·cos^n α in cos α; φ uniform.
  const float c = std::pow(u.x, 1.0f / (exponent + 1.0f));
  const float s = std::sqrt(std::max(0.0f, 1.0f - c * c));
  const float phi = 2.0f * kPi * u.y;
  const Frame frame = Frame::fromNormal(glm::normalize(specular::reflect(wKnown)));
  const Vec3 w = glm::normalize(frame.toWorld(Vec3(s * std::cos(phi), s * std::sin(phi), c)));
  const float p = pdf(wKnown, w, exponent);
  if (p <= 0.0f) return std::nullopt;
  return DirectionSample{w, p, false};
}

}  // namespace kasha::gloss
