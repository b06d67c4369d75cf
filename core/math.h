#pragma once
// Vector types and small geometric helpers shared by every module.
#include <glm/glm.hpp>
#include <cmath>
#include <limits>

namespace kasha {

using Vec2 = glm::vec2;
using Vec3 = glm::vec3;

inline constexpr float kPi = 3.14159265358979323846f;
inline constexpr float kInvPi = 1.0f / kPi;
inline constexpr float kInf = std::numeric_limits<float>::infinity();
// The largest float below 1: where a rescaled uniform must stay in [0, 1).
inline constexpr float kBelowOne = 0x1.fffffep-1f;

inline float sqr(float x) { return x * x; }

// Orthonormal frame around a unit normal n (Duff et al. 2017, "Building an orthonormal basis,
// revisited"). Local coordinates have z along n.
struct Frame {
  Vec3 s, t, n;

  static Frame fromNormal(const Vec3& n) {
    const float sign = std::copysign(1.0f, n.z);
    const float a = -1.0f / (sign + n.z);
    const float b = n.x * n.y * a;
    return {Vec3(1.0f + sign * n.x * n.x * a, sign * b, -sign * n.x), Vec3(b, sign + n.y * n.y * a, -n.y), n};
  }
  Vec3 toLocal(const Vec3& v) const { return {glm::dot(v, s), glm::dot(v, t), glm::dot(v, n)}; }
  Vec3 toWorld(const Vec3& v) const { return v.x * s + v.y * t + v.z * n; }
};

}  // namespace kasha
