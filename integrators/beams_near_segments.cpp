#include "integrators/beams_near_segments.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "integrators/segment_hits.h"

namespace kasha {

struct BeamsNearSegments::Shared {
  const std::vector<Beam>* beams;
  float radius;
};

namespace {

// The squared distance between the segments p + s·u, s in [0, a], and q + t·v, t in [0, b] (u, v of
// unit length): the closest points of the lines, clamped into the segments one after the other
// (Ericson, Real-Time Collision Detection, §5.1.9).
float segmentDistance2(const Vec3& p, const Vec3& u, float a, const Vec3& q, const Vec3& v, float b) {
  const Vec3 r = p - q;
  const float uv = glm::dot(u, v), ur = glm::dot(u, r), vr = glm::dot(v, r);
  const float denom = 1.0f - uv * uv;
  float s = denom > 1e-8f ? std::clamp((uv * vr - ur) / denom, 0.0f, a) : 0.0f;
  float t = std::clamp(uv * s + vr, 0.0f, b);
  s = std::clamp(uv * t - ur, 0.0f, a);
  const Vec3 gap = (p + s * u) - (q + t * v);
  return glm::dot(gap, gap);
}


void capsuleBounds(const RTCBoundsFunctionArguments* args) {
  const auto* all = static_cast<const BeamsNearSegments::Shared*>(args->geometryUserPtr);
  const BeamsNearSegments::Beam& b = (*all->beams)[args->primID];
  const Vec3 e = b.a + b.w * b.length;
  const Vec3 lo = glm::min(b.a, e) - all->radius, hi = glm::max(b.a, e) + all->radius;
  args->bounds_o->lower_x = lo.x, args->bounds_o->lower_y = lo.y, args->bounds_o->lower_z = lo.z;
  args->bounds_o->upper_x = hi.x, args->bounds_o->upper_y = hi.y, args->bounds_o->upper_z = hi.z;
}

// Embree calls this for every capsule whose bounds the query's segment meets: the segment is near the
// beam if it comes within the radius of it, wherever it starts (also inside the capsule).
void capsuleNearSegment(const RTCIntersectFunctionNArguments* args) {
  if (!args->valid[0]) return;
  const auto* all = static_cast<const BeamsNearSegments::Shared*>(args->geometryUserPtr);
  const BeamsNearSegments::Beam& b = (*all->beams)[args->primID];
  RTCRayN* ray = RTCRayHitN_RayN(args->rayhit, args->N);
  const Vec3 o(RTCRayN_org_x(ray, args->N, 0), RTCRayN_org_y(ray, args->N, 0), RTCRayN_org_z(ray, args->N, 0));
  const Vec3 d(RTCRayN_dir_x(ray, args->N, 0), RTCRayN_dir_y(ray, args->N, 0), RTCRayN_dir_z(ray, args->N, 0));
  const float length = RTCRayN_tfar(ray, args->N, 0);
  if (segmentDistance2(o, d, length, b.a, b.w, b.length) < all->radius * all->radius) recordMet(args->context, args->primID);
}

}  // namespace

BeamsNearSegments::BeamsNearSegments(const std::vector<Beam>& beams, float radius) : beams_(beams), radius_(radius) {
  if (!(radius > 0.0f)) throw std::invalid_argument("BeamsNearSegments: the radius must be positive");
  device_ = rtcNewDevice("verbose=0");
  scene_ = rtcNewScene(device_);
  rtcSetSceneFlags(scene_, RTC_SCENE_FLAG_ROBUST);
  user_ = std::make_unique<Shared>(Shared{&beams_, radius_});
  if (!beams_.empty()) {
    RTCGeometry g = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_USER);
    rtcSetGeometryUserPrimitiveCount(g, unsigned(beams_.size()));
    rtcSetGeometryUserData(g, user_.get());
    rtcSetGeometryBoundsFunction(g, capsuleBounds, nullptr);
    rtcSetGeometryIntersectFunction(g, capsuleNearSegment);
    rtcCommitGeometry(g);
    rtcAttachGeometry(scene_, g);
    rtcReleaseGeometry(g);
  }
  rtcCommitScene(scene_);
}

BeamsNearSegments::~BeamsNearSegments() {
  rtcReleaseScene(scene_);
  rtcReleaseDevice(device_);
}

void BeamsNearSegments::near(const Vec3& o, const Vec3& d, float length, std::vector<uint32_t>& found) const {
  found.clear();
  // Embree asserts a finite origin and direction.
  const bool finite = std::isfinite(o.x) && std::isfinite(o.y) && std::isfinite(o.z) && std::isfinite(d.x) &&
                      std::isfinite(d.y) && std::isfinite(d.z) && std::isfinite(length);
  if (beams_.empty() || !finite || !(length >= 0.0f)) return;
  hitsAlong(scene_, o, d, length, found);
  std::sort(found.begin(), found.end());
  found.erase(std::unique(found.begin(), found.end()), found.end());
}

}  // namespace kasha
