#pragma once
// The directional part shared by smooth (specular) materials, in the local frame of the geometric
// normal (z up). Directions point away from the surface on both sides of an event.
//
// A specular lobe is a Dirac delta in direction. Materials leave the delta out: its direction
// density is the discrete probability of choosing the lobe, and f is the delta's coefficient
// (material.h). Sampling produces the lobe's direction exactly; matches() accepts a direction
// that was carried through frame changes or recomputed from positions.
#include <cmath>
#include <optional>

#include "core/math.h"

namespace kasha::specular {

// Mirror direction about the normal.
inline Vec3 reflect(const Vec3& w) { return Vec3(-w.x, -w.y, w.z); }

// Direction transmitted through the interface from the side of w (w.z ≠ 0), where eta is the
// relative index η_far/η_w of the far side over w's side; nothing under total internal reflection.
// Snell's law n_w·sin θ_w = n_far·sin θ_t with the tangential part reversed (the light goes on
// through): ω_t = −ω/η + (cos θ_w/η − cos θ_t)·n, n the normal on w's side (pbrt-v4 §9.3),
// whose normal component is −cos θ_t·n.
inline std::optional<Vec3> refract(const Vec3& w, float eta) {
  const float cosW = std::abs(w.z);
  const float sin2T = (1.0f - cosW * cosW) / (eta * eta);
  if (sin2T >= 1.0f) return std::nullopt;
  const float cosT = std::sqrt(1.0f - sin2T);
  return Vec3(-w.x / eta, -w.y / eta, w.z > 0.0f ? -cosT : cosT);
}

// Whether a unit direction is the lobe's direction up to rounding: within about 1.4 mrad.
inline bool matches(const Vec3& w, const Vec3& lobeDirection) { return glm::dot(w, lobeDirection) > 1.0f - 1e-6f; }

}  // namespace kasha::specular
