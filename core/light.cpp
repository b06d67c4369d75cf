#include "core/light.h"

#include <algorithm>

#include "core/sampling.h"

namespace kasha {

std::optional<LightSample> AreaLight::sampleLi(const Vec3& p, float lambda, Vec2 u) const {
  const SurfaceSample s = shape_.sampleUniform(u);
  Vec3 d = s.p - p;
  const float dist2 = glm::dot(d, d);
  if (!(dist2 > 0.0f)) return std::nullopt;
  const float dist = std::sqrt(dist2);
  d /= dist;
  const float cosLight = std::abs(glm::dot(s.ng, d));
  if (cosLight <= 0.0f) return std::nullopt;
  const float Li = shape_.emission->eval(lambda, s.ng, -d);
  // area density → solid angle: p_ω = p_A · d² / |cos θ_l|
  return LightSample{d, dist, Li, s.pdfArea * dist2 / cosLight, false};
}

float AreaLight::pdfLi(const Vec3& p, const Vec3& pl, const Vec3& nl) const {
  const Vec3 d = pl - p;
  const float dist2 = glm::dot(d, d);
  const float cosLight = std::abs(glm::dot(nl, d)) / std::sqrt(dist2);
  return cosLight > 0.0f ? dist2 / (cosLight * shape_.area) : 0.0f;
}

float AreaLight::power(float lambda) const {
  const AreaEmission& e = *shape_.emission;
  return kPi * shape_.area * e.scale * e.radiance(lambda) * (e.twoSided ? 2.0f : 1.0f);
}

std::optional<LightSample> PointLight::sampleLi(const Vec3& p, float lambda, Vec2) const {
  const Vec3 d = pos_ - p;
  const float dist2 = glm::dot(d, d);
  if (!(dist2 > 0.0f)) return std::nullopt;
  const float dist = std::sqrt(dist2);
  return LightSample{d / dist, dist, scale_ * I_(lambda) / dist2, 1.0f, true};
}

SpotLight::SpotLight(Vec3 position, Vec3 direction, float coneDeg, float falloffDeg, Spectrum intensity, float scale)
    : pos_(position),
      dir_(glm::normalize(direction)),
      cosTotal_(std::cos(coneDeg * kPi / 180.0f)),
      cosStart_(std::cos(std::min(falloffDeg, coneDeg) * kPi / 180.0f)),
      I_(std::move(intensity)),
      scale_(scale) {}

float SpotLight::falloff(float cosTheta) const {
  if (cosTheta >= cosStart_) return 1.0f;
  if (cosTheta <= cosTotal_) return 0.0f;
  const float t = (cosTheta - cosTotal_) / (cosStart_ - cosTotal_);
  return t * t * (3.0f - 2.0f * t);
}

std::optional<LightSample> SpotLight::sampleLi(const Vec3& p, float lambda, Vec2) const {
  const Vec3 d = pos_ - p;
  const float dist2 = glm::dot(d, d);
  if (!(dist2 > 0.0f)) return std::nullopt;
  const float dist = std::sqrt(dist2);
  const Vec3 wi = d / dist;
  return LightSample{wi, dist, scale_ * I_(lambda) * falloff(glm::dot(-wi, dir_)) / dist2, 1.0f, true};
}

float SpotLight::power(float lambda) const {
  // ∫ falloff dω ≈ 2π(1 − (cosStart + cosTotal)/2): exact for a linear ramp, close for the cubic.
  return scale_ * I_(lambda) * 2.0f * kPi * (1.0f - 0.5f * (cosStart_ + cosTotal_));
}

std::optional<LightSample> DistantLight::sampleLi(const Vec3&, float lambda, Vec2) const {
  return LightSample{-dir_, kInf, scale_ * E_(lambda), 1.0f, true};
}

std::optional<LightSample> EnvironmentLight::sampleLi(const Vec3&, float lambda, Vec2 u) const {
  return LightSample{sampleUniformSphere(u), kInf, Le(lambda), kUniformSpherePdf, false};
}

float EnvironmentLight::pdfDirection() const { return kUniformSpherePdf; }

std::pair<size_t, float> LightSelector::select(float lambda, float u) const {
  float total = 0.0f;
  for (const auto& l : lights_) total += l->power(lambda);
  if (!(total > 0.0f)) return {0, 0.0f};
  float acc = 0.0f;
  const float target = u * total;
  size_t last = 0;
  for (size_t i = 0; i < lights_.size(); ++i) {
    const float p = lights_[i]->power(lambda);
    if (p <= 0.0f) continue;
    last = i;
    acc += p;
    if (target < acc) return {i, p / total};
  }
  return {last, lights_[last]->power(lambda) / total};
}

float LightSelector::probability(size_t light, float lambda) const {
  float total = 0.0f;
  for (const auto& l : lights_) total += l->power(lambda);
  return total > 0.0f ? lights_[light]->power(lambda) / total : 0.0f;
}

}  // namespace kasha
