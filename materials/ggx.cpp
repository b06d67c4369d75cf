#include "materials/ggx.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace kasha {

float Ggx::d(const Vec3& m) const {
  if (m.z <= 0.0f) return 0.0f;
  const float k = sqr(m.x / ax_) + sqr(m.y / ay_) + sqr(m.z);
  return 1.0f / (kPi * ax_ * ay_ * k * k);
}

float Ggx::lambda(const Vec3& w) const {
  if (w.z == 0.0f) return kInf;
  const float tan2 = (sqr(ax_ * w.x) + sqr(ay_ * w.y)) / sqr(w.z);
  return 0.5f * (std::sqrt(1.0f + tan2) - 1.0f);
}

float Ggx::visiblePdf(const Vec3& w, const Vec3& m) const {
  if (w.z == 0.0f) return 0.0f;
  const float wm = glm::dot(w, m) * (w.z > 0.0f ? 1.0f : -1.0f);
  if (wm <= 0.0f) return 0.0f;
  return g1(w) * wm * d(m) / std::abs(w.z);
}

Vec3 Ggx::sampleVisible(const Vec3& w, Vec2 u) const {
  const Vec3 wUp = w.z < 0.0f ? -w : w;
  // Stretched view direction (the α = 1 configuration).
  const Vec3 v = glm::normalize(Vec3(ax_ * wUp.x, ay_ * wUp.y, wUp.z));
  // Orthonormal basis around v with t1 horizontal.
  const float len2 = v.x * v.x + v.y * v.y;
  const Vec3 t1 = len2 > 0.0f ? Vec3(-v.y, v.x, 0.0f) / std::sqrt(len2) : Vec3(1.0f, 0.0f, 0.0f);
  const Vec3 t2 = glm::cross(v, t1);
  // Uniform point on the disk, its half beyond the horizon squeezed by s = (1 + v_z)/2.
  const float r = std::sqrt(u.x), phi = 2.0f * kPi * u.y;
  const float p1 = r * std::cos(phi);
  const float s = 0.5f * (1.0f + v.z);
  const float p2 = (1.0f - s) * std::sqrt(std::max(0.0f, 1.0f - p1 * p1)) + s * r * std::sin(phi);
  // Project onto the hemisphere around v, then unstretch.
  const Vec3 n = p1 * t1 + p2 * t2 + std::sqrt(std::max(0.0f, 1.0f - p1 * p1 - p2 * p2)) * v;
  return glm::normalize(Vec3(ax_ * n.x, ay_ * n.y, std::max(1e-7f, n.z)));
}

float Ggx::reflection(const Vec3& a, const Vec3& b) const {
  if (a.z * b.z <= 0.0f) return 0.0f;
  return d(reflectionHalfVector(a, b)) * g1(a) * g1(b) / (4.0f * std::abs(a.z) * std::abs(b.z));
}

float Ggx::reflectionPdf(const Vec3& a, const Vec3& b) const {
  if (a.z * b.z <= 0.0f) return 0.0f;
  const Vec3 h = reflectionHalfVector(a, b);
  return visiblePdf(a, h) / (4.0f * std::abs(glm::dot(a, h)));
}

Ggx checkedGgx(float alphaX, float alphaY) {
  for (const float a : {alphaX, alphaY})
    if (!(a >= kMinAlpha && a <= kMaxAlpha))
      throw std::invalid_argument("alpha: roughness " + std::to_string(a) + " is outside [0.001, 1]");
  return Ggx(alphaX, alphaY);
}

Vec3 reflectionHalfVector(const Vec3& a, const Vec3& b) {
  const Vec3 h = glm::normalize(a + b);
  return h.z < 0.0f ? -h : h;
}

Vec3 refractionHalfVector(const Vec3& a, float etaA, const Vec3& b, float etaB) {
  const Vec3 h = glm::normalize(etaA * a + etaB * b);
  return h.z < 0.0f ? -h : h;
}

Vec3 reflectAbout(const Vec3& w, const Vec3& m) { return 2.0f * glm::dot(w, m) * m - w; }

bool refractAbout(const Vec3& w, const Vec3& m, float eta, Vec3& t) {
  const float c = glm::dot(w, m);
  const Vec3 ms = c < 0.0f ? -m : m;  // the facet normal on w's side
  const float cosW = std::abs(c);
  const float cos2T = 1.0f - (1.0f - cosW * cosW) / (eta * eta);
  if (cos2T <= 0.0f) return false;
  t = glm::normalize(-w / eta + (cosW / eta - std::sqrt(cos2T)) * ms);
  return true;
}

}  // namespace kasha
