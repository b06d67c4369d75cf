#pragma once
#include "core/math.h"

namespace kasha {

struct Ray {
  Vec3 o, d;  // d is unit length
  float tMax = kInf;
};

// Where a ray stopped: a point on a shape, with the geometric normal as the frame's z.
struct Hit {
  float t = kInf;
  Vec3 p;
  Vec3 ng;  // unit geometric normal (outward for spheres, right-handed winding for triangles, Cylinder::normal)
  uint32_t shape = 0;
  uint32_t prim = 0;
  Vec2 bary{0.0f};  // barycentrics of triangle corners 1 and 2; a cylinder's (φ/2π, z/length) (for Shape::surfaceUv)
};

// Offset for rays leaving a surface: relative to the magnitude of the position.
inline float rayEpsilon(const Vec3& p) {
  return 2e-5f * (1.0f + std::max(std::abs(p.x), std::max(std::abs(p.y), std::abs(p.z))));
}
// A point just off the surface on the side of direction d.
inline Vec3 offsetPoint(const Vec3& p, const Vec3& ng, const Vec3& d) {
  const float eps = rayEpsilon(p);
  return glm::dot(ng, d) >= 0.0f ? p + eps * ng : p - eps * ng;
}

}  // namespace kasha
