#pragma once
// Light sources: area (an emissive shape), point, spot, distant and a uniform environment. Each
// has a spectrum and a scale; all quantities are evaluated at one wavelength.
#include <memory>
#include <optional>
#include <vector>

#include "core/shape.h"

namespace kasha {

struct LightSample {
  Vec3 wi;           // from the receiving point towards the light
  float dist = kInf; // distance to the light point (infinite for distant and environment)
  float Li = 0.0f;   // incident radiance (for delta lights: intensity/d² or irradiance)
  float pdf = 0.0f;  // per steradian at the receiver; 1 for delta lights
  bool delta = false;
};

struct SceneBounds {
  Vec3 center{0.0f};
  float radius = 1.0f;
};

class Light {
 public:
  virtual ~Light() = default;
  // Samples a direction towards the light from point p at wavelength lambda.
  virtual std::optional<LightSample> sampleLi(const Vec3& p, float lambda, Vec2 u) const = 0;
  // Solid-angle density of sampleLi choosing the point pl (normal nl) seen from p; area and
  // environment lights only (delta lights cannot be hit).
  virtual float pdfLi(const Vec3& p, const Vec3& pl, const Vec3& nl) const { return 0.0f; }
  // Emitted power at lambda, up to a common factor: used to choose among lights.
  virtual float power(float lambda) const = 0;
  virtual bool isDelta() const { return false; }
};

class AreaLight final : public Light {
 public:
  explicit AreaLight(const Shape& shape) : shape_(shape) {}
  std::optional<LightSample> sampleLi(const Vec3& p, float lambda, Vec2 u) const override;
  float pdfLi(const Vec3& p, const Vec3& pl, const Vec3& nl) const override;
  float power(float lambda) const override;
  const Shape& shape() const { return shape_; }

 private:
  const Shape& shape_;
};

class PointLight final : public Light {
 public:
  PointLight(Vec3 position, Spectrum intensity, float scale) : pos_(position), I_(std::move(intensity)), scale_(scale) {}
  std::optional<LightSample> sampleLi(const Vec3& p, float lambda, Vec2 u) const override;
  float power(float lambda) const override { return 4.0f * kPi * scale_ * I_(lambda); }
  bool isDelta() const override { return true; }

 private:
  Vec3 pos_;
  Spectrum I_;
  float scale_;
};

// Intensity I inside cosFalloffStart, smoothly to zero at cosTotal (cubic Hermite in cos θ).
class SpotLight final : public Light {
 public:
  SpotLight(Vec3 position, Vec3 direction, float coneDeg, float falloffDeg, Spectrum intensity, float scale);
  std::optional<LightSample> sampleLi(const Vec3& p, float lambda, Vec2 u) const override;
  float power(float lambda) const override;
  bool isDelta() const override { return true; }
  float falloff(float cosTheta) const;

 private:
  Vec3 pos_, dir_;
  float cosTotal_, cosStart_;
  Spectrum I_;
  float scale_;
};

// Parallel light travelling along `direction`, irradiance E on a perpendicular plane.
class DistantLight final : public Light {
 public:
  DistantLight(Vec3 direction, Spectrum irradiance, float scale, SceneBounds bounds)
      : dir_(glm::normalize(direction)), E_(std::move(irradiance)), scale_(scale), bounds_(bounds) {}
  std::optional<LightSample> sampleLi(const Vec3& p, float lambda, Vec2 u) const override;
  float power(float lambda) const override { return kPi * sqr(bounds_.radius) * scale_ * E_(lambda); }
  bool isDelta() const override { return true; }
  float irradiance(float lambda) const { return scale_ * E_(lambda); }
  const Vec3& direction() const { return dir_; }

 private:
  Vec3 dir_;
  Spectrum E_;
  float scale_;
  SceneBounds bounds_;
};

// Radiance L arriving from every direction at infinity; sampled uniformly over the sphere.
class EnvironmentLight final : public Light {
 public:
  EnvironmentLight(Spectrum radiance, float scale, SceneBounds bounds)
      : L_(std::move(radiance)), scale_(scale), bounds_(bounds) {}
  std::optional<LightSample> sampleLi(const Vec3& p, float lambda, Vec2 u) const override;
  float pdfDirection() const;
  float power(float lambda) const override { return 4.0f * kPi * kPi * sqr(bounds_.radius) * Le(lambda); }
  float Le(float lambda) const { return scale_ * L_(lambda); }

 private:
  Spectrum L_;
  float scale_;
  SceneBounds bounds_;
};

// Chooses a light in proportion to its power at the path's wavelength, so that at a UV
// wavelength only UV sources are picked.
class LightSelector {
 public:
  explicit LightSelector(const std::vector<std::unique_ptr<Light>>& lights) : lights_(lights) {}
  // Returns the index of the chosen light and its probability, or probability 0.
  std::pair<size_t, float> select(float lambda, float u) const;
  float probability(size_t light, float lambda) const;

 private:
  const std::vector<std::unique_ptr<Light>>& lights_;
};

}  // namespace kasha
