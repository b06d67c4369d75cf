#pragma once
// Points near a ray segment, the query of the beam radiance estimate (Jarosz et al. 2008; photon
// points against the camera's query beam, docs/media-beams.md): which of a set of points lie within
// radius r of the segment, across it (their nearest point on its line inside it). The points are
// Embree spheres of radius r (RTC_GEOMETRY_TYPE_SPHERE_POINT) in a scene of their own, and a query
// is one Embree ray that records every sphere it meets (segment_hits.h); the spheres that hold the whole segment, which the ray never meets,
// hold its origin, and a FLANN ball query there (point_map.h) finds them.
#include <embree3/rtcore.h>

#include <cstdint>
#include <memory>
#include <vector>

#include "core/math.h"
#include "integrators/point_map.h"

namespace kasha {

class PointsNearSegments {
 public:
  // A point found: its index in the points given, and the distance along the segment to its nearest
  // point there.
  struct Found {
    uint32_t index;
    float t;
  };

  PointsNearSegments(const std::vector<Vec3>& points, float radius);
  ~PointsNearSegments();
  PointsNearSegments(const PointsNearSegments&) = delete;
  PointsNearSegments& operator=(const PointsNearSegments&) = delete;

  // The points at distance < r from the line o + t·d (d of unit length) with t in [0, length], in
  // increasing index. `found` belongs to the caller and is overwritten.
  void near(const Vec3& o, const Vec3& d, float length, std::vector<Found>& found) const;
  float radius() const { return radius_; }

 private:
  struct Record {
    float p[3];  // first: a PointMap record
    uint32_t index;
  };
  std::vector<Vec3> points_;
  float radius_;
  RTCDevice device_ = nullptr;
  RTCScene scene_ = nullptr;
  std::unique_ptr<PointMap<Record>> map_;
};

}  // namespace kasha
