#include "integrators/points_near_segments.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "integrators/point_map_impl.h"
#include "integrators/segment_hits.h"

namespace kasha {

PointsNearSegments::PointsNearSegments(const std::vector<Vec3>& points, float radius)
    : points_(points), radius_(radius) {
  if (!(radius > 0.0f)) throw std::invalid_argument("PointsNearSegments: the radius must be positive");
  device_ = rtcNewDevice("verbose=0");
  scene_ = rtcNewScene(device_);
  rtcSetSceneFlags(scene_, RTC_SCENE_FLAG_ROBUST);
  std::vector<Record> records(points.size());
  if (!points.empty()) {
    RTCGeometry g = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_SPHERE_POINT);
    auto* v = static_cast<float*>(
        rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT4, 4 * sizeof(float), points.size()));
    for (size_t i = 0; i < points.size(); ++i) {
      v[4 * i] = points[i].x, v[4 * i + 1] = points[i].y, v[4 * i + 2] = points[i].z, v[4 * i + 3] = radius;
      records[i] = {{points[i].x, points[i].y, points[i].z}, uint32_t(i)};
    }
    collectEveryHit(g);
    rtcCommitGeometry(g);
    rtcAttachGeometry(scene_, g);
    rtcReleaseGeometry(g);
  }
  rtcCommitScene(scene_);
  map_ = std::make_unique<PointMap<Record>>(std::move(records));
}

PointsNearSegments::~PointsNearSegments() {
  rtcReleaseScene(scene_);
  rtcReleaseDevice(device_);
}

void PointsNearSegments::near(const Vec3& o, const Vec3& d, float length, std::vector<Found>& found) const {
  found.clear();
  thread_local std::vector<uint32_t> met;
  met.clear();
  // Embree asserts a finite origin and direction.
  const bool finite = std::isfinite(o.x) && std::isfinite(o.y) && std::isfinite(o.z) && std::isfinite(d.x) &&
                      std::isfinite(d.y) && std::isfinite(d.z);
  if (points_.empty() || !finite || !(length >= 0.0f)) return;
  hitsAlong(scene_, o, d, length, met);
  for (size_t i : map_->within(o, radius_)) met.push_back((*map_)[i].index);  // the map reorders its records
  std::sort(met.begin(), met.end());
  met.erase(std::unique(met.begin(), met.end()), met.end());
  const float r2 = radius_ * radius_;
  for (uint32_t i : met) {
    const Vec3 x = points_[i] - o;
    const float t = glm::dot(x, d);
    if (t < 0.0f || t > length) continue;
    const Vec3 across = x - t * d;
    if (glm::dot(across, across) < r2) found.push_back({i, t});
  }
}

}  // namespace kasha
