#pragma once
// The directional part shared by diffuse materials: two-sided Lambertian reflection, cosine-
// weighted about the normal on the known direction's side. Reciprocal: pdf(a→b) = |cos b|/π.
#include <optional>

#include "core/sampling.h"
#include "materials/material.h"

namespace kasha::diffuse {

inline bool sameSide(const Vec3& a, const Vec3& b) { return a.z * b.z > 0.0f; }

inline std::optional<DirectionSample> sample(const Vec3& wKnown, Vec2 u) {
  if (wKnown.z == 0.0f) return std::nullopt;
  Vec3 w = sampleCosineHemisphere(u);
  if (w.z <= 0.0f) return std::nullopt;
  if (wKnown.z < 0.0f) w.z = -w.z;
  return DirectionSample{w, cosineHemispherePdf(std::abs(w.z)), false};
}

inline float pdf(const Vec3& wKnown, const Vec3& wSampled) {
  return sameSide(wKnown, wSampled) ? cosineHemispherePdf(std::abs(wSampled.z)) : 0.0f;
}

}  // namespace kasha::diffuse

namespace kasha {

// The directional stage of a model whose every lobe is diffuse (the functions above), on top of
// its spectral stage: Base is BsdfModel (the model writes its own) or ElasticModel.
template <class Base>
class DiffuseModel : public Base {
 public:
  std::optional<DirectionSample> sampleDirection(const ScatterQuery&, const Vec3& wKnown, Vec2 u) const final {
    return diffuse::sample(wKnown, u);
  }
  float directionPdf(const ScatterQuery&, const Vec3& wKnown, const Vec3& wSampled) const final {
    return diffuse::pdf(wKnown, wSampled);
  }

 protected:
  ~DiffuseModel() = default;
};

}  // namespace kasha
