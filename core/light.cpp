#include "core/light.h"

#include <algorithm>

#include "core/sampling.h"

namespace kasha {
namespace {

// A unit disk of radius r perpendicular to d, centred on c: a uniform point on it.
Vec3 pointOnDisk(const Vec3& c, const Vec3& d, float r, Vec2 u) {
  const Frame f = Frame::fromNormal(d);
  const Vec2 q = sampleConcentricDisk(u) * r;
  return c + q.x * f.s + q.y * f.t;
}

}  // namespace

// ---- area ----------------------------------------------------------------------------------

AreaLight::AreaLight(const Shape& shape)
    : Light(shape.emission->radiance, shape.emission->scale,
            kPi * shape.area * (shape.emission->twoSided ? 2.0f : 1.0f)),
      shape_(shape) {}

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
  return LightSample{d, dist, Li, s.pdfArea * dist2 / cosLight, false, s.ng};
}

float AreaLight::Li(const LightSample& s, float lambda) const { return shape_.emission->eval(lambda, s.n, -s.wi); }

float AreaLight::pdfLi(const Vec3& p, const Vec3& pl, const Vec3& nl) const {
  const Vec3 d = pl - p;
  const float dist2 = glm::dot(d, d);
  const float cosLight = std::abs(glm::dot(nl, d)) / std::sqrt(dist2);
  return cosLight > 0.0f ? dist2 / (cosLight * shape_.area) : 0.0f;
}

std::optional<EmissionSample> AreaLight::sampleEmission(float lambda, Vec2 uPos, Vec2 uDir) const {
  const SurfaceSample s = shape_.sampleUniform(uPos);
  const AreaEmission& e = *shape_.emission;
  Vec3 n = s.ng;
  Vec2 u = uDir;
  if (e.twoSided) {  // pick a side with probability 1/2, reusing u.x
    if (u.x < 0.5f) {
      u.x *= 2.0f;
    } else {
      u.x = std::min(2.0f * u.x - 1.0f, 0x1.fffffep-1f);
      n = -n;
    }
  }
  const Vec3 local = sampleCosineHemisphere(u);
  if (local.z <= 0.0f) return std::nullopt;
  EmissionSample es;
  es.p = s.p;
  es.n = s.ng;
  es.w = Frame::fromNormal(n).toWorld(local);
  es.Le = e.eval(lambda, s.ng, es.w);
  es.cosOrigin = local.z;
  es.pdfPos = s.pdfArea;
  es.pdfDir = pdfEmissionDirection(s.ng, es.w);
  return es;
}

float AreaLight::emitted(const EmissionSample& s, float lambda) const { return shape_.emission->eval(lambda, s.n, s.w); }

void AreaLight::emissionPdfs(const Vec3&, const Vec3& n, const Vec3& w, float& pdfPos, float& pdfDir) const {
  pdfPos = 1.0f / shape_.area;
  pdfDir = pdfEmissionDirection(n, w);
}

float AreaLight::pdfEmissionDirection(const Vec3& n, const Vec3& w) const {
  const float c = glm::dot(n, w);
  if (shape_.emission->twoSided) return 0.5f * std::abs(c) * kInvPi;
  return c > 0.0f ? c * kInvPi : 0.0f;
}

// ---- point ---------------------------------------------------------------------------------

std::optional<LightSample> PointLight::sampleLi(const Vec3& p, float lambda, Vec2) const {
  return sampleLightPoint(p, pos_, [&](const Vec3&) { return intensity(lambda); });
}

float PointLight::Li(const LightSample& s, float lambda) const { return intensity(lambda) / (s.dist * s.dist); }

std::optional<EmissionSample> PointLight::sampleEmission(float lambda, Vec2, Vec2 uDir) const {
  EmissionSample es;
  es.p = pos_;
  es.w = sampleUniformSphere(uDir);
  es.Le = intensity(lambda);
  es.pdfPos = 1.0f;
  es.pdfDir = kUniformSpherePdf;
  es.deltaPos = true;
  return es;
}

float PointLight::emitted(const EmissionSample&, float lambda) const { return intensity(lambda); }

void PointLight::emissionPdfs(const Vec3&, const Vec3&, const Vec3&, float& pdfPos, float& pdfDir) const {
  pdfPos = 1.0f;
  pdfDir = kUniformSpherePdf;
}

// ---- spot ----------------------------------------------------------------------------------

SpotLight::SpotLight(Vec3 position, Vec3 direction, float coneDeg, float falloffDeg, Spectrum intensity, float scale,
                     const RgbImage* texture, Vec3 up)
    : Light(std::move(intensity), scale, 0.0f),
      pos_(position),
      dir_(glm::normalize(direction)),
      cosTotal_(std::cos(coneDeg * kPi / 180.0f)),
      cosStart_(std::cos(std::min(falloffDeg, coneDeg) * kPi / 180.0f)) {
  if (texture) {
    // Mitsuba's (u, v) above is the projected image's (core/projected_image.h) in the look-at frame
    // turned by 180° about the axis: (−left, −up, forward).
    const Frame f = lookAtFrame(position, position + direction, up);
    const float tanCone = std::tan(coneDeg * kPi / 180.0f);
    texture_.emplace(*texture, Frame{-f.s, -f.t, f.n}, tanCone, tanCone,
                     [this](const Vec3& local) { return falloff(local.z) * local.z * local.z * local.z; });
    // ∫ T_Y·falloff dω over the cone, from above at each texel's nearest point (steers light selection).
    powerFactor_ = float(texture_->weightIntegral());
  } else {
    // ∫ falloff dω ≈ 2π(1 − (cosStart + cosTotal)/2): exact for a linear ramp, close for the cubic;
    // it only steers light selection.
    powerFactor_ = 2.0f * kPi * (1.0f - 0.5f * (cosStart_ + cosTotal_));
  }
}

float SpotLight::falloff(float cosTheta) const {
  if (cosTheta >= cosStart_) return 1.0f;
  if (cosTheta <= cosTotal_) return 0.0f;
  const float t = (cosTheta - cosTotal_) / (cosStart_ - cosTotal_);
  return t * t * (3.0f - 2.0f * t);
}

std::optional<Vec2> SpotLight::directionToUv(const Vec3& w) const {
  return texture_ ? texture_->directionToUv(w) : std::nullopt;
}

float SpotLight::emittedTowards(float lambda, const Vec3&, const Vec3& w) const {
  const float f = falloff(glm::dot(w, dir_));
  if (!(f > 0.0f)) return 0.0f;
  const float I = scale_ * spectrum_(lambda) * f;
  if (!texture_) return I;
  const std::optional<Vec2> uv = texture_->directionToUv(w);  // inside the cone, inside the image
  return uv ? I * texture_->texel(*uv).modulation(lambda) : 0.0f;
}

std::optional<LightSample> SpotLight::sampleLi(const Vec3& p, float lambda, Vec2) const {
  return sampleLightPoint(p, pos_, [&](const Vec3& w) { return emittedTowards(lambda, Vec3(0.0f), w); });
}

float SpotLight::Li(const LightSample& s, float lambda) const {
  return emittedTowards(lambda, Vec3(0.0f), -s.wi) / (s.dist * s.dist);
}

std::optional<EmissionSample> SpotLight::sampleEmission(float lambda, Vec2, Vec2 uDir) const {
  EmissionSample es;
  es.p = pos_;
  es.pdfPos = 1.0f;
  es.deltaPos = true;
  if (texture_) {
    const std::optional<ProjectedImage::Sample> s = texture_->sample(uDir);
    // A texel across the cone's edge: its part outside emits nothing at any λ.
    if (!s || !(falloff(s->cosTheta) > 0.0f)) return std::nullopt;
    es.w = s->w;
    es.pdfDir = s->pdf;
    es.Le = emittedTowards(lambda, Vec3(0.0f), es.w);
  } else {
    const Vec3 local = sampleUniformCone(uDir, cosTotal_);
    es.w = Frame::fromNormal(dir_).toWorld(local);
    es.pdfDir = 1.0f / (2.0f * kPi * (1.0f - cosTotal_));
    es.Le = scale_ * spectrum_(lambda) * falloff(local.z);  // the cone's own cosine
  }
  return es;
}

float SpotLight::emitted(const EmissionSample& s, float lambda) const { return emittedTowards(lambda, s.n, s.w); }

void SpotLight::emissionPdfs(const Vec3&, const Vec3&, const Vec3& w, float& pdfPos, float& pdfDir) const {
  pdfPos = 1.0f;
  if (texture_)
    pdfDir = texture_->pdf(w);
  else
    pdfDir = glm::dot(w, dir_) >= cosTotal_ ? 1.0f / (2.0f * kPi * (1.0f - cosTotal_)) : 0.0f;
}

// ---- distant -------------------------------------------------------------------------------

std::optional<LightSample> DistantLight::sampleLi(const Vec3&, float lambda, Vec2) const {
  return LightSample{-dir_, kInf, irradiance(lambda), 1.0f, true};
}

float DistantLight::Li(const LightSample&, float lambda) const { return irradiance(lambda); }

std::optional<EmissionSample> DistantLight::sampleEmission(float lambda, Vec2 uPos, Vec2) const {
  // A uniform point on the disk of the scene's bounding radius, upstream of the scene.
  EmissionSample es;
  es.p = pointOnDisk(bounds_.center - dir_ * bounds_.radius, dir_, bounds_.radius, uPos);
  es.w = dir_;
  es.Le = irradiance(lambda);
  es.pdfPos = 1.0f / (kPi * sqr(bounds_.radius));
  es.pdfDir = 1.0f;
  es.deltaDir = true;
  return es;
}

float DistantLight::emitted(const EmissionSample&, float lambda) const { return irradiance(lambda); }

void DistantLight::emissionPdfs(const Vec3&, const Vec3&, const Vec3&, float& pdfPos, float& pdfDir) const {
  pdfPos = 1.0f / (kPi * sqr(bounds_.radius));
  pdfDir = 1.0f;
}

// ---- environment ---------------------------------------------------------------------------

std::pair<Vec3, float> EnvironmentLight::sampleDirection(Vec2 u) const { return {sampleUniformSphere(u), kUniformSpherePdf}; }

float EnvironmentLight::pdfDirection(const Vec3&) const { return kUniformSpherePdf; }

std::optional<LightSample> EnvironmentLight::sampleLi(const Vec3&, float lambda, Vec2 u) const {
  const auto [wi, pdf] = sampleDirection(u);
  if (!(pdf > 0.0f)) return std::nullopt;
  return LightSample{wi, kInf, Le(lambda, wi), pdf, false};
}

float EnvironmentLight::Li(const LightSample& s, float lambda) const { return Le(lambda, s.wi); }

std::optional<EmissionSample> EnvironmentLight::sampleEmission(float lambda, Vec2 uPos, Vec2 uDir) const {
  // Direction of travel w against a sampled direction towards the environment, then a uniform
  // point on the disk facing it.
  const auto [towards, pdf] = sampleDirection(uDir);
  if (!(pdf > 0.0f)) return std::nullopt;
  EmissionSample es;
  es.w = -towards;
  es.p = pointOnDisk(bounds_.center - es.w * bounds_.radius, es.w, bounds_.radius, uPos);
  es.Le = Le(lambda, towards);
  es.pdfPos = 1.0f / (kPi * sqr(bounds_.radius));
  es.pdfDir = pdf;
  return es;
}

float EnvironmentLight::emitted(const EmissionSample& s, float lambda) const { return Le(lambda, -s.w); }

void EnvironmentLight::emissionPdfs(const Vec3&, const Vec3&, const Vec3& w, float& pdfPos, float& pdfDir) const {
  pdfPos = 1.0f / (kPi * sqr(bounds_.radius));
  pdfDir = pdfDirection(-w);
}

}  // namespace kasha
