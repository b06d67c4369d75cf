#pragma once
// Ray queries against the scene's shapes through Embree 3: triangle meshes as
// RTC_GEOMETRY_TYPE_TRIANGLE, spheres as RTC_GEOMETRY_TYPE_SPHERE_POINT, cylinders as
// RTC_GEOMETRY_TYPE_USER calling Cylinder::intersect. Geometry IDs equal shape indices.
#include <embree3/rtcore.h>

#include <optional>
#include <vector>

#include "core/light.h"
#include "core/shape.h"

namespace kasha {

class Accel {
 public:
  explicit Accel(const std::vector<Shape>& shapes);
  ~Accel();
  Accel(const Accel&) = delete;
  Accel& operator=(const Accel&) = delete;

  std::optional<Hit> intersect(const Ray& ray) const;
  // True if anything blocks the open segment from o along unit d up to distance tMax.
  bool occluded(const Vec3& o, const Vec3& d, float tMax) const;
  SceneBounds bounds() const { return bounds_; }
  // The Embree scene, for baselines that call Embree directly.
  RTCScene handle() const { return scene_; }

 private:
  RTCDevice device_ = nullptr;
  RTCScene scene_ = nullptr;
  const std::vector<Shape>& shapes_;
  SceneBounds bounds_;
};

}  // namespace kasha
