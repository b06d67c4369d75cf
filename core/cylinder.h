#pragma once
// The analytic open cylinder, a tube without caps (Mitsuba 3 docs: "Cylinder"): the points
//   x(φ, z) = base + radius·(cos φ·s + sin φ·t) + z·a,   φ ∈ [0, 2π), z ∈ [0, length],
// with (s, t, a) an orthonormal frame, a the axis. Its surface parameters are (φ/2π, z/length), as
// Mitsuba's uv; its normal is the outward radial direction cos φ·s + sin φ·t, or the inward one
// when flipped (Mitsuba's flip_normals).
#include <glm/mat4x4.hpp>

#include <optional>

#include "core/math.h"

namespace kasha {

struct CylinderHit {
  float t;
  Vec2 param;  // (φ/2π, z/length), both in [0, 1]
};

struct Cylinder {
  Vec3 base{0.0f};                                             // the centre of the circle z = 0 (Mitsuba's p0)
  Frame frame{Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)};   // s: φ = 0; t: φ = π/2; n: the axis a
  float radius = 1.0f, length = 1.0f;
  bool inward = false;  // the normal points at the axis

  // Mitsuba's placement of the unit cylinder (radius 1, z ∈ [0, 1] along +z) from its ends and
  // radius: translate(p0)·[frame around (p1 − p0), Duff et al. 2017]·scale(radius, radius, |p1 − p0|).
  static glm::mat4 endsMatrix(const Vec3& p0, const Vec3& p1, float radius);
  // The unit cylinder mapped by the affine m, if m keeps it a circular cylinder: m's images of x
  // and y orthogonal and of equal length, both orthogonal to its image of z, and no mirroring
  // (which would turn Mitsuba's normal inwards); else nullopt. Relative tolerance 10⁻⁴.
  static std::optional<Cylinder> fromMatrix(const glm::mat4& m);

  float area() const { return 2.0f * kPi * radius * length; }
  // The nearest intersection of the ray o + t·d (d unit) with t in (tMin, tMax), if any. The
  // quadratic |(o + t·d − base)_⊥|² = radius² is solved in double precision in the frame, its
  // roots taken in order; a root outside z ∈ [0, length] lets the ray go on to the other one,
  // since the tube has no caps.
  std::optional<CylinderHit> intersect(const Vec3& o, const Vec3& d, float tMin, float tMax) const;
  Vec3 point(Vec2 param) const;
  // The unit normal at param: outward, or inward if flipped.
  Vec3 normal(Vec2 param) const;
  // A point uniform by area: φ = 2π·u.y, z = length·u.x (density 1/area).
  Vec2 sampleParam(Vec2 u) const { return Vec2(u.y, u.x); }
  // Axis-aligned bounds: the end circles' extents, radius·√(1 − a_i²) along axis i.
  void bounds(Vec3& lo, Vec3& hi) const;
};

}  // namespace kasha
