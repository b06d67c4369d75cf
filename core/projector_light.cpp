#include "core/projector_light.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace kasha {

ProjectorLight::ProjectorLight(Vec3 position, Vec3 lookAt, Vec3 up, float fovXDegrees, const RgbImage& image,
                               float scale, WavelengthRange range)
    : Light(Spectrum::constant(0.0f), scale, 0.0f),
      pos_(position),
      tanX_(std::tan(0.5f * fovXDegrees * kPi / 180.0f)),
      tanY_(tanX_ * float(image.height) / float(image.width)),
      w_(image.width),
      h_(image.height),
      texels_(upsampleTexels(image)),
      distribution_(texelLuminances(image), image.width, image.height) {
  if (distribution_.empty()) throw std::runtime_error("the projector's image is black");
  // Mitsuba's look-at: forward z, left x = up × z, up y = z × x.
  const Vec3 z = glm::normalize(lookAt - position);
  const Vec3 x = glm::normalize(glm::cross(up, z));
  frame_ = Frame{x, glm::cross(z, x), z};
  spectrum_ = meanTexelSpectrum(texels_, std::vector<float>(texels_.size(), 1.0f), double(texels_.size()), range);
  powerFactor_ = kPi * 4.0f * tanX_ * tanY_;  // ∫I dω = π·scale·∫E dA over the plane z = 1
}

std::optional<Vec2> ProjectorLight::directionToUv(const Vec3& w) const {
  const Vec3 local = frame_.toLocal(w);
  if (!(local.z > 0.0f)) return std::nullopt;
  const Vec2 uv(0.5f * (1.0f - local.x / (local.z * tanX_)), 0.5f * (1.0f - local.y / (local.z * tanY_)));
  if (!(uv.x >= 0.0f && uv.x <= 1.0f && uv.y >= 0.0f && uv.y <= 1.0f)) return std::nullopt;
  return uv;
}

const RgbIlluminant& ProjectorLight::texel(Vec2 uv) const {
  const int x = std::min(int(uv.x * float(w_)), w_ - 1), y = std::min(int(uv.y * float(h_)), h_ - 1);
  return texels_[size_t(y) * size_t(w_) + size_t(x)];
}

float ProjectorLight::emittedTowards(float lambda, const Vec3&, const Vec3& w) const {
  const std::optional<Vec2> uv = directionToUv(w);
  if (!uv) return 0.0f;
  const float cosTheta = glm::dot(w, frame_.n);
  return kPi * scale_ * texel(*uv)(lambda) / (cosTheta * cosTheta * cosTheta);
}

std::optional<LightSample> ProjectorLight::sampleLi(const Vec3& p, float lambda, Vec2) const {
  return sampleLightPoint(p, pos_, [&](const Vec3& w) { return emittedTowards(lambda, Vec3(0.0f), w); });
}

float ProjectorLight::Li(const LightSample& s, float lambda) const {
  return emittedTowards(lambda, Vec3(0.0f), -s.wi) / (s.dist * s.dist);
}

std::optional<EmissionSample> ProjectorLight::sampleEmission(float lambda, Vec2, Vec2 uDir) const {
  const Distribution2D::Sample s = distribution_.sample(uDir);
  if (!(s.pdf > 0.0f)) return std::nullopt;
  // The point of the image plane z = 1 at (u, v), and its direction.
  const Vec3 q((1.0f - 2.0f * s.uv.x) * tanX_, (1.0f - 2.0f * s.uv.y) * tanY_, 1.0f);
  const Vec3 local = glm::normalize(q);
  const float cos3 = local.z * local.z * local.z;
  EmissionSample es;
  es.p = pos_;
  es.w = frame_.toWorld(local);
  es.Le = kPi * scale_ * texel(s.uv)(lambda) / cos3;
  es.pdfPos = 1.0f;
  es.pdfDir = s.pdf / (4.0f * tanX_ * tanY_ * cos3);
  es.deltaPos = true;
  return es;
}

float ProjectorLight::emitted(const EmissionSample& s, float lambda) const { return emittedTowards(lambda, s.n, s.w); }

void ProjectorLight::emissionPdfs(const Vec3&, const Vec3&, const Vec3& w, float& pdfPos, float& pdfDir) const {
  pdfPos = 1.0f;
  pdfDir = 0.0f;
  const std::optional<Vec2> uv = directionToUv(w);
  if (!uv) return;
  const float c = glm::dot(w, frame_.n);
  pdfDir = distribution_.pdf(*uv) / (4.0f * tanX_ * tanY_ * c * c * c);
}

}  // namespace kasha
