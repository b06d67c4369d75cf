#include "core/cylinder.h"

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>

namespace kasha {

glm::mat4 Cylinder::endsMatrix(const Vec3& p0, const Vec3& p1, float radius) {
  const Vec3 d = p1 - p0;
  const float length = glm::length(d);
  const Frame f = Frame::fromNormal(d / length);
  glm::mat4 m(1.0f);
  m[0] = glm::vec4(radius * f.s, 0.0f);
  m[1] = glm::vec4(radius * f.t, 0.0f);
  m[2] = glm::vec4(length * f.n, 0.0f);
  m[3] = glm::vec4(p0, 1.0f);
  return m;
}

std::optional<Cylinder> Cylinder::fromMatrix(const glm::mat4& m) {
  const Vec3 x(m[0]), y(m[1]), z(m[2]);
  const float r = glm::length(x), len = glm::length(z);
  constexpr float kTolerance = 1e-4f;
  if (!(r > 0.0f) || !(len > 0.0f) || !std::isfinite(r) || !std::isfinite(len)) return std::nullopt;
  if (std::abs(glm::length(y) - r) > kTolerance * r || std::abs(glm::dot(x, y)) > kTolerance * r * r ||
      std::abs(glm::dot(x, z)) > kTolerance * r * len || std::abs(glm::dot(y, z)) > kTolerance * r * len ||
      !(glm::dot(glm::cross(x, y), z) > 0.0f))
    return std::nullopt;
  Cylinder c;
  c.base = Vec3(m[3]);
  c.radius = r;
  c.length = len;
  c.frame.n = z / len;
  c.frame.s = glm::normalize(x - glm::dot(x, c.frame.n) * c.frame.n);
  c.frame.t = glm::cross(c.frame.n, c.frame.s);  // right-handed: y's direction up to the tolerance
  return c;
}

std::optional<CylinderHit> Cylinder::intersect(const Vec3& o, const Vec3& d, float tMin, float tMax) const {
  // The ray in the frame, in double precision: o' = ((o − base)·s, (o − base)·t, (o − base)·a).
  const glm::dvec3 rel = glm::dvec3(o) - glm::dvec3(base);
  const glm::dvec3 s(frame.s), t(frame.t), n(frame.n), dir(d);
  const double ox = glm::dot(rel, s), oy = glm::dot(rel, t), oz = glm::dot(rel, n);
  const double dx = glm::dot(dir, s), dy = glm::dot(dir, t), dz = glm::dot(dir, n);
  // a t² + b t + c = 0 for the distance to the axis; a = 0: parallel to the axis, never on the tube.
  const double a = dx * dx + dy * dy, b = 2.0 * (ox * dx + oy * dy);
  const double c = ox * ox + oy * oy - double(radius) * double(radius);
  const double discriminant = b * b - 4.0 * a * c;
  if (!(a > 0.0) || discriminant < 0.0) return std::nullopt;
  // The roots without cancellation (PBR4 §6.8.1): q = −(b + sign(b)·√Δ)/2, t0 = q/a, t1 = c/q.
  const double q = -0.5 * (b + std::copysign(std::sqrt(discriminant), b));
  double roots[2] = {q / a, q != 0.0 ? c / q : q / a};
  if (roots[0] > roots[1]) std::swap(roots[0], roots[1]);
  for (const double root : roots) {
    if (!(root > double(tMin) && root < double(tMax))) continue;
    const double z = oz + root * dz;
    if (z < 0.0 || z > double(length)) continue;
    const double px = ox + root * dx, py = oy + root * dy;
    double phi = std::atan2(py, px);
    if (phi < 0.0) phi += 2.0 * M_PI;
    const float u = std::min(float(phi / (2.0 * M_PI)), 0x1.fffffep-1f);
    return CylinderHit{float(root), Vec2(u, std::clamp(float(z / double(length)), 0.0f, 1.0f))};
  }
  return std::nullopt;
}

Vec3 Cylinder::point(Vec2 param) const {
  const float phi = 2.0f * kPi * param.x;
  return base + radius * (std::cos(phi) * frame.s + std::sin(phi) * frame.t) + length * param.y * frame.n;
}

Vec3 Cylinder::normal(Vec2 param) const {
  const float phi = 2.0f * kPi * param.x;
  const Vec3 outward = std::cos(phi) * frame.s + std::sin(phi) * frame.t;
  return inward ? -outward : outward;
}

void Cylinder::bounds(Vec3& lo, Vec3& hi) const {
  const Vec3 top = base + length * frame.n;
  Vec3 extent;
  for (int i = 0; i < 3; ++i) extent[i] = radius * std::sqrt(std::max(0.0f, 1.0f - frame.n[i] * frame.n[i]));
  // Padded by a little more than float rounding of the points on the rims.
  extent += 1e-6f * (radius + glm::length(base) + length);
  lo = glm::min(base, top) - extent;
  hi = glm::max(base, top) + extent;
}

}  // namespace kasha
