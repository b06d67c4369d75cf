#include "core/shape.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <tuple>

#include "core/sampling.h"

namespace kasha {

size_t Shape::finalize() {
  if (kind == Kind::Sphere) {
    area = 4.0f * kPi * radius * radius;
    return 0;
  }
  if (kind == Kind::Cylinder) {
    area = cylinder.area();
    return 0;
  }
  std::vector<uint32_t> kept;
  std::vector<Vec2> keptUvs;
  std::vector<Vec3> keptNormals;
  std::vector<std::vector<Vec3>> keptFaceValues(attributes.size());
  size_t removed = 0;
  triangleCdf.clear();
  normals.clear();
  double acc = 0.0;
  for (size_t t = 0; t + 2 < indices.size(); t += 3) {
    const Vec3 a = positions[indices[t]], b = positions[indices[t + 1]], c = positions[indices[t + 2]];
    const float triArea = 0.5f * glm::length(glm::cross(b - a, c - a));
    if (!(triArea > 0.0f)) {
      ++removed;
      continue;
    }
    kept.insert(kept.end(), {indices[t], indices[t + 1], indices[t + 2]});
    if (!cornerUvs.empty()) keptUvs.insert(keptUvs.end(), {cornerUvs[t], cornerUvs[t + 1], cornerUvs[t + 2]});
    if (!cornerNormals.empty())
      keptNormals.insert(keptNormals.end(), {cornerNormals[t], cornerNormals[t + 1], cornerNormals[t + 2]});
    for (size_t a = 0; a < attributes.size(); ++a)
      if (attributes[a].perFace()) keptFaceValues[a].push_back(attributes[a].values[t / 3]);
    normals.push_back(glm::normalize(glm::cross(b - a, c - a)));
    acc += triArea;
    triangleCdf.push_back(float(acc));
  }
  indices = std::move(kept);
  cornerUvs = std::move(keptUvs);
  cornerNormals = std::move(keptNormals);
  for (size_t a = 0; a < attributes.size(); ++a)
    if (attributes[a].perFace()) attributes[a].values = std::move(keptFaceValues[a]);
  area = float(acc);
  return removed;
}

Vec2 Shape::surfaceUv(uint32_t prim, Vec2 bary, const Vec3& n) const {
  if (kind == Kind::Sphere) {
    const Vec3 l = glm::transpose(sphereAxes) * n;
    float u = 0.5f + std::atan2(l.z, l.x) / (2.0f * kPi);
    if (u >= 1.0f) u -= 1.0f;
    return Vec2(u, std::acos(std::clamp(-l.y, -1.0f, 1.0f)) / kPi);
  }
  if (kind == Kind::Cylinder) return Vec2(bary.x, 1.0f - bary.y);
  if (cornerUvs.empty()) return Vec2(0.0f);
  const size_t t = 3 * size_t(prim);
  return (1.0f - bary.x - bary.y) * cornerUvs[t] + bary.x * cornerUvs[t + 1] + bary.y * cornerUvs[t + 2];
}

Shape::UvDerivatives Shape::uvDerivatives(uint32_t prim, const Vec3& n) const {
  if (kind == Kind::Sphere) {
    const Vec3 l = glm::transpose(sphereAxes) * n;
    const float rho = std::sqrt(l.x * l.x + l.z * l.z);
    if (!(rho > 1e-6f)) {  // a pole: u is undefined there
      const Frame f = Frame::fromNormal(n);
      return {f.s, f.t};
    }
    return {sphereAxes * (2.0f * kPi * radius * Vec3(-l.z, 0.0f, l.x)),
            sphereAxes * (kPi * radius * Vec3(-l.y * l.x / rho, rho, -l.y * l.z / rho))};
  }
  if (kind == Kind::Cylinder) {
    // x = base + r·(cos φ·s + sin φ·t) + z·a with φ = 2πu, z = length·(1 − v) (surfaceUv).
    const Cylinder& c = cylinder;
    const Vec3 radial = c.inward ? -n : n;
    const float cosPhi = glm::dot(radial, c.frame.s), sinPhi = glm::dot(radial, c.frame.t);
    return {2.0f * kPi * c.radius * (cosPhi * c.frame.t - sinPhi * c.frame.s), -c.length * c.frame.n};
  }
  const size_t t = 3 * size_t(prim);
  const Frame around = Frame::fromNormal(normals[prim]);
  if (cornerUvs.empty()) return {around.s, around.t};
  // p0 − p2 = (u0 − u2)·∂p/∂u + (v0 − v2)·∂p/∂v, and the same for p1 − p2 (PBR4 eq. 6.7).
  const Vec3 dp02 = positions[indices[t]] - positions[indices[t + 2]], dp12 = positions[indices[t + 1]] - positions[indices[t + 2]];
  const Vec2 duv02 = cornerUvs[t] - cornerUvs[t + 2], duv12 = cornerUvs[t + 1] - cornerUvs[t + 2];
  const float det = duv02.x * duv12.y - duv02.y * duv12.x;
  const Vec3 dpdu = (duv12.y * dp02 - duv02.y * dp12) / det, dpdv = (duv02.x * dp12 - duv12.x * dp02) / det;
  const float cross = glm::length(glm::cross(dpdu, dpdv));
  if (!(cross > 0.0f) || !std::isfinite(cross)) return {around.s, around.t};
  return {dpdu, dpdv};
}

Vec3 Shape::shadingNormal(uint32_t prim, Vec2 bary, const Vec3& ng) const {
  if (kind != Kind::Mesh || cornerNormals.empty()) return ng;
  const size_t t = 3 * size_t(prim);
  const Vec3 n = (1.0f - bary.x - bary.y) * cornerNormals[t] + bary.x * cornerNormals[t + 1] + bary.y * cornerNormals[t + 2];
  const float len = glm::length(n);
  if (!(len > 1e-12f) || !std::isfinite(len)) return ng;
  return glm::dot(n, ng) < 0.0f ? -n / len : n / len;
}

const MeshAttribute* Shape::attribute(const std::string& name) const {
  for (const MeshAttribute& a : attributes)
    if (a.name == name) return &a;
  return nullptr;
}

Vec3 Shape::attributeAt(const MeshAttribute& a, uint32_t prim, Vec2 bary) const {
  if (a.perFace()) return a.values[prim];
  const size_t t = 3 * size_t(prim);
  return (1.0f - bary.x - bary.y) * a.values[indices[t]] + bary.x * a.values[indices[t + 1]] +
         bary.y * a.values[indices[t + 2]];
}

SurfaceSample Shape::sampleUniform(Vec2 u) const {
  if (kind == Kind::Sphere) {
    const Vec3 n = sampleUniformSphere(u);
    return {center + radius * n, n, 1.0f / area};
  }
  if (kind == Kind::Cylinder) {
    const Vec2 param = cylinder.sampleParam(u);
    return {cylinder.point(param), cylinder.normal(param), 1.0f / area};
  }
  // Pick a triangle by area, reuse u.x within it.
  const float target = u.x * area;
  size_t t = size_t(std::upper_bound(triangleCdf.begin(), triangleCdf.end(), target) - triangleCdf.begin());
  t = std::min(t, triangleCdf.size() - 1);
  const float lo = t == 0 ? 0.0f : triangleCdf[t - 1];
  const float ux = std::clamp((target - lo) / std::max(triangleCdf[t] - lo, 1e-30f), 0.0f, 0x1.fffffep-1f);
  const Vec2 b = sampleUniformTriangle(Vec2(ux, u.y));
  const Vec3 a = positions[indices[3 * t]], bb = positions[indices[3 * t + 1]], c = positions[indices[3 * t + 2]];
  const Vec3 p = b.x * a + b.y * bb + (1.0f - b.x - b.y) * c;
  return {p, triangleNormal(uint32_t(t)), 1.0f / area};
}

bool Shape::closed() const {
  if (kind == Kind::Sphere) return true;
  if (kind == Kind::Cylinder) return false;
  return openEdges() == 0;
}

size_t Shape::openEdges() const {
  // Edges by their end positions (meshes may repeat a position under several indices).
  const auto key = [](const Vec3& a, const Vec3& b) {
    const auto less = [](const Vec3& x, const Vec3& y) { return std::tie(x.x, x.y, x.z) < std::tie(y.x, y.y, y.z); };
    return less(a, b) ? std::array<float, 6>{a.x, a.y, a.z, b.x, b.y, b.z} : std::array<float, 6>{b.x, b.y, b.z, a.x, a.y, a.z};
  };
  std::map<std::array<float, 6>, int> uses;
  for (size_t t = 0; t + 2 < indices.size(); t += 3)
    for (int e = 0; e < 3; ++e) ++uses[key(positions[indices[t + size_t(e)]], positions[indices[t + size_t((e + 1) % 3)]])];
  return size_t(std::count_if(uses.begin(), uses.end(), [](const auto& u) { return u.second != 2; }));
}

}  // namespace kasha
