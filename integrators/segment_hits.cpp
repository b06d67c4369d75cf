#include "integrators/segment_hits.h"

namespace kasha {
namespace {

// Embree hands the filter the intersection context it was given, so the list follows it.
struct Collecting {
  RTCIntersectContext context;
  std::vector<uint32_t>* met;
};

void recordAndReject(const RTCFilterFunctionNArguments* args) {
  const auto* query = reinterpret_cast<const Collecting*>(args->context);
  query->met->push_back(RTCHitN_primID(args->hit, args->N, 0));
  args->valid[0] = 0;
}

}  // namespace

void recordMet(RTCIntersectContext* context, uint32_t prim) {
  reinterpret_cast<const Collecting*>(context)->met->push_back(prim);
}

void collectEveryHit(RTCGeometry g) { rtcSetGeometryIntersectFilterFunction(g, recordAndReject); }

void hitsAlong(RTCScene scene, const Vec3& o, const Vec3& d, float length, std::vector<uint32_t>& met) {
  Collecting q;
  rtcInitIntersectContext(&q.context);
  q.met = &met;
  RTCRayHit rh{};
  rh.ray.org_x = o.x, rh.ray.org_y = o.y, rh.ray.org_z = o.z;
  rh.ray.dir_x = d.x, rh.ray.dir_y = d.y, rh.ray.dir_z = d.z;
  rh.ray.tnear = 0.0f, rh.ray.tfar = length, rh.ray.mask = ~0u;
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rtcIntersect1(scene, &q.context, &rh);
}

}  // namespace kasha
