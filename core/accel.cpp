#include "core/accel.h"

#include <stdexcept>
#include <string>

namespace kasha {
namespace {

// Embree user geometry for a Cylinder (its geometryUserPtr): bounds, and the exact intersection
// for each valid ray of a packet of N (rtcIntersect1 and rtcOccluded1 pass N = 1).
void cylinderBounds(const RTCBoundsFunctionArguments* args) {
  Vec3 lo, hi;
  static_cast<const Cylinder*>(args->geometryUserPtr)->bounds(lo, hi);
  *args->bounds_o = RTCBounds{lo.x, lo.y, lo.z, 0.0f, hi.x, hi.y, hi.z, 0.0f};
}

std::optional<CylinderHit> cylinderHit(const Cylinder& c, RTCRayN* ray, unsigned n, unsigned i) {
  const Vec3 o(RTCRayN_org_x(ray, n, i), RTCRayN_org_y(ray, n, i), RTCRayN_org_z(ray, n, i));
  const Vec3 d(RTCRayN_dir_x(ray, n, i), RTCRayN_dir_y(ray, n, i), RTCRayN_dir_z(ray, n, i));
  return c.intersect(o, d, RTCRayN_tnear(ray, n, i), RTCRayN_tfar(ray, n, i));
}

void cylinderIntersect(const RTCIntersectFunctionNArguments* args) {
  const Cylinder& c = *static_cast<const Cylinder*>(args->geometryUserPtr);
  RTCRayN* ray = RTCRayHitN_RayN(args->rayhit, args->N);
  RTCHitN* hit = RTCRayHitN_HitN(args->rayhit, args->N);
  for (unsigned i = 0; i < args->N; ++i) {
    if (args->valid[i] == 0) continue;
    const std::optional<CylinderHit> h = cylinderHit(c, ray, args->N, i);
    if (!h) continue;
    const Vec3 n = c.normal(h->param);
    RTCRayN_tfar(ray, args->N, i) = h->t;
    RTCHitN_Ng_x(hit, args->N, i) = n.x, RTCHitN_Ng_y(hit, args->N, i) = n.y, RTCHitN_Ng_z(hit, args->N, i) = n.z;
    RTCHitN_u(hit, args->N, i) = h->param.x, RTCHitN_v(hit, args->N, i) = h->param.y;
    RTCHitN_primID(hit, args->N, i) = args->primID;
    RTCHitN_geomID(hit, args->N, i) = args->geomID;
    RTCHitN_instID(hit, args->N, i, 0) = args->context->instID[0];
  }
}

void cylinderOccluded(const RTCOccludedFunctionNArguments* args) {
  const Cylinder& c = *static_cast<const Cylinder*>(args->geometryUserPtr);
  for (unsigned i = 0; i < args->N; ++i)
    if (args->valid[i] != 0 && cylinderHit(c, args->ray, args->N, i)) RTCRayN_tfar(args->ray, args->N, i) = -kInf;
}

}  // namespace

Accel::Accel(const std::vector<Shape>& shapes) : shapes_(shapes) {
  device_ = rtcNewDevice("verbose=0");
  if (!device_) throw std::runtime_error("Embree: cannot create a device");
  scene_ = rtcNewScene(device_);
  rtcSetSceneBuildQuality(scene_, RTC_BUILD_QUALITY_HIGH);
  Vec3 lo(kInf), hi(-kInf);
  for (size_t i = 0; i < shapes.size(); ++i) {
    const Shape& s = shapes[i];
    RTCGeometry g;
    if (s.kind == Shape::Kind::Sphere) {
      g = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_SPHERE_POINT);
      auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT4, 4 * sizeof(float), 1));
      v[0] = s.center.x, v[1] = s.center.y, v[2] = s.center.z, v[3] = s.radius;
      lo = glm::min(lo, s.center - Vec3(s.radius));
      hi = glm::max(hi, s.center + Vec3(s.radius));
    } else if (s.kind == Shape::Kind::Cylinder) {
      g = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_USER);
      rtcSetGeometryUserPrimitiveCount(g, 1);
      rtcSetGeometryUserData(g, const_cast<Cylinder*>(&s.cylinder));
      rtcSetGeometryBoundsFunction(g, cylinderBounds, nullptr);
      rtcSetGeometryIntersectFunction(g, cylinderIntersect);
      rtcSetGeometryOccludedFunction(g, cylinderOccluded);
      Vec3 clo, chi;
      s.cylinder.bounds(clo, chi);
      lo = glm::min(lo, clo);
      hi = glm::max(hi, chi);
    } else {
      g = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_TRIANGLE);
      auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), s.positions.size()));
      for (size_t k = 0; k < s.positions.size(); ++k) {
        v[3 * k] = s.positions[k].x, v[3 * k + 1] = s.positions[k].y, v[3 * k + 2] = s.positions[k].z;
        lo = glm::min(lo, s.positions[k]);
        hi = glm::max(hi, s.positions[k]);
      }
      auto* idx = static_cast<unsigned*>(rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned), s.indices.size() / 3));
      std::copy(s.indices.begin(), s.indices.end(), idx);
    }
    rtcCommitGeometry(g);
    rtcAttachGeometryByID(scene_, g, unsigned(i));
    rtcReleaseGeometry(g);
  }
  rtcCommitScene(scene_);
  if (const RTCError err = rtcGetDeviceError(device_); err != RTC_ERROR_NONE)
    throw std::runtime_error("Embree failed to build the scene (error " + std::to_string(int(err)) + ")");
  if (lo.x <= hi.x) bounds_ = {0.5f * (lo + hi), std::max(0.5f * glm::length(hi - lo), 1e-3f)};
}

Accel::~Accel() {
  if (scene_) rtcReleaseScene(scene_);
  if (device_) rtcReleaseDevice(device_);
}

std::optional<Hit> Accel::intersect(const Ray& ray) const {
  RTCIntersectContext ctx;
  rtcInitIntersectContext(&ctx);
  RTCRayHit rh;
  rh.ray.org_x = ray.o.x, rh.ray.org_y = ray.o.y, rh.ray.org_z = ray.o.z;
  rh.ray.dir_x = ray.d.x, rh.ray.dir_y = ray.d.y, rh.ray.dir_z = ray.d.z;
  rh.ray.tnear = 0.0f;
  rh.ray.tfar = ray.tMax;
  rh.ray.mask = 0xFFFFFFFF;
  rh.ray.flags = 0;
  rh.ray.time = 0.0f;
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
  rtcIntersect1(scene_, &ctx, &rh);
  if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return std::nullopt;
  Hit h;
  h.t = rh.ray.tfar;
  h.p = ray.o + h.t * ray.d;
  h.shape = rh.hit.geomID;
  h.prim = rh.hit.primID;
  const Shape& s = shapes_[h.shape];
  if (s.kind == Shape::Kind::Sphere) {
    h.ng = glm::normalize(h.p - s.center);
    h.p = s.center + s.radius * h.ng;  // re-project for precision
  } else if (s.kind == Shape::Kind::Cylinder) {
    const Vec2 param(rh.hit.u, rh.hit.v);
    h.ng = s.cylinder.normal(param);
    h.p = s.cylinder.point(param);  // re-project for precision
  } else {
    h.ng = s.triangleNormal(h.prim);
  }
  h.bary = Vec2(rh.hit.u, rh.hit.v);
  return h;
}

bool Accel::occluded(const Vec3& o, const Vec3& d, float tMax) const {
  RTCIntersectContext ctx;
  rtcInitIntersectContext(&ctx);
  RTCRay r;
  r.org_x = o.x, r.org_y = o.y, r.org_z = o.z;
  r.dir_x = d.x, r.dir_y = d.y, r.dir_z = d.z;
  r.tnear = 0.0f;
  r.tfar = tMax;
  r.mask = 0xFFFFFFFF;
  r.flags = 0;
  r.time = 0.0f;
  rtcOccluded1(scene_, &ctx, &r);
  return r.tfar < 0.0f;
}

}  // namespace kasha
