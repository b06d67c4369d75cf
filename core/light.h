#pragma once
// Light sources: area (an emissive shape), point, spot (textured or not), distant and a uniform
// environment. Each has a spectrum and a scale; every quantity is evaluated at one wavelength.
// Lights are sampled from a receiving point (next-event estimation: sampleLi) and as the start of
// light subpaths (sampleEmission), with the densities both need for MIS.
#include <memory>
#include <cmath>
#include <optional>
#include <vector>

#include "core/projected_image.h"
#include "core/shape.h"
#include "core/spectral_distribution.h"

namespace kasha {

struct LightSample {
  Vec3 wi;           // from the receiving point towards the light
  float dist = kInf; // distance to the light point (infinite for distant and environment)
  float Li = 0.0f;   // incident radiance (for delta lights: intensity/d² or irradiance)
  float pdf = 0.0f;  // per steradian at the receiver; 1 for delta lights
  bool delta = false;
  Vec3 n{0.0f};      // normal at the light point (area lights)
};

// The start of a light subpath. Its weight is Le·cosOrigin / (pdfPos·pdfDir).
struct EmissionSample {
  Vec3 p;                  // origin
  Vec3 n{0.0f};            // emitter normal at p (area lights), else zero
  Vec3 w;                  // direction of travel
  float Le = 0.0f;         // radiance (area, environment), intensity (point, spot), irradiance (distant)
  float cosOrigin = 1.0f;  // |cos| between n and w for area lights, else 1
  float pdfPos = 0.0f;     // per unit area (1 for point and spot lights)
  float pdfDir = 0.0f;     // per steradian (1 for distant lights)
  bool deltaPos = false, deltaDir = false;
};

struct SceneBounds {
  Vec3 center{0.0f};
  float radius = 1.0f;
};

class Light {
 public:
  Light(Spectrum spectrum, float scale, float powerFactor)
      : spectrum_(std::move(spectrum)), scale_(scale), powerFactor_(powerFactor) {}
  virtual ~Light() = default;
  // Samples a direction towards the light from point p at wavelength lambda.
  virtual std::optional<LightSample> sampleLi(const Vec3& p, float lambda, Vec2 u) const = 0;
  // The Li of a sample sampleLi took, at another wavelength: the sample's geometry does not depend
  // on λ, so wavelength lanes share it.
  virtual float Li(const LightSample& s, float lambda) const = 0;
  // Solid-angle density of sampleLi choosing the point pl (normal nl) seen from p; area and
  // environment lights only (delta lights cannot be hit).
  virtual float pdfLi(const Vec3& p, const Vec3& pl, const Vec3& nl) const { return 0.0f; }
  // Samples the origin and direction of a light subpath at wavelength lambda.
  virtual std::optional<EmissionSample> sampleEmission(float lambda, Vec2 uPos, Vec2 uDir) const = 0;
  // The Le of a sample sampleEmission took, at another wavelength (its geometry does not depend on λ).
  virtual float emitted(const EmissionSample& s, float lambda) const = 0;
  // The densities sampleEmission would have for leaving point p (normal n) along w: per area
  // (per area of the disk for lights at infinity) and per steradian.
  virtual void emissionPdfs(const Vec3& p, const Vec3& n, const Vec3& w, float& pdfPos, float& pdfDir) const = 0;
  virtual bool isDelta() const { return false; }
  // What a light at a finite position emits from its point p (normal n) along w: radiance for
  // area lights, intensity for point and spot lights; 0 for lights at infinity.
  virtual float emittedTowards(float lambda, const Vec3& n, const Vec3& w) const { return 0.0f; }
  // Distant and environment lights: vertices at infinity, densities per steradian.
  virtual bool atInfinity() const { return false; }

  // Emitted power at lambda (W/nm up to the scene's unit): powerFactor·scale·spectrum(λ).
  float power(float lambda) const { return powerFactor_ * scale_ * spectrum_(lambda); }
  const Spectrum& spectrum() const { return spectrum_; }
  float scale() const { return scale_; }
  float powerFactor() const { return powerFactor_; }

 protected:
  Spectrum spectrum_;
  float scale_;
  float powerFactor_;  // geometric factor turning scale·spectrum into power
};

// sampleLi of a light at one point `at` seen from p: the direction toward it, its distance, and
// Li = I(w)/d² with I(w) the intensity `intensity` gives along w, the direction leaving the light;
// nullopt where p is the light's point.
template <class Intensity>
std::optional<LightSample> sampleLightPoint(const Vec3& p, const Vec3& at, const Intensity& intensity) {
  const Vec3 d = at - p;
  const float dist2 = glm::dot(d, d);
  if (!(dist2 > 0.0f)) return std::nullopt;
  const float dist = std::sqrt(dist2);
  const Vec3 wi = d / dist;
  return LightSample{wi, dist, intensity(-wi) / dist2, 1.0f, true};
}

class AreaLight final : public Light {
 public:
  explicit AreaLight(const Shape& shape);
  std::optional<LightSample> sampleLi(const Vec3& p, float lambda, Vec2 u) const override;
  float Li(const LightSample& s, float lambda) const override;
  float pdfLi(const Vec3& p, const Vec3& pl, const Vec3& nl) const override;
  std::optional<EmissionSample> sampleEmission(float lambda, Vec2 uPos, Vec2 uDir) const override;
  float emitted(const EmissionSample& s, float lambda) const override;
  void emissionPdfs(const Vec3& p, const Vec3& n, const Vec3& w, float& pdfPos, float& pdfDir) const override;
  // Solid-angle density of sampleEmission's direction w leaving a point with normal n.
  float pdfEmissionDirection(const Vec3& n, const Vec3& w) const;
  float emittedTowards(float lambda, const Vec3& n, const Vec3& w) const override {
    return shape_.emission->eval(lambda, n, w);
  }
  const Shape& shape() const { return shape_; }

 private:
  const Shape& shape_;
};

class PointLight final : public Light {
 public:
  PointLight(Vec3 position, Spectrum intensity, float scale)
      : Light(std::move(intensity), scale, 4.0f * kPi), pos_(position) {}
  std::optional<LightSample> sampleLi(const Vec3& p, float lambda, Vec2 u) const override;
  float Li(const LightSample& s, float lambda) const override;
  std::optional<EmissionSample> sampleEmission(float lambda, Vec2 uPos, Vec2 uDir) const override;
  float emitted(const EmissionSample& s, float lambda) const override;
  void emissionPdfs(const Vec3& p, const Vec3& n, const Vec3& w, float& pdfPos, float& pdfDir) const override;
  bool isDelta() const override { return true; }
  float intensity(float lambda) const { return scale_ * spectrum_(lambda); }
  float emittedTowards(float lambda, const Vec3&, const Vec3&) const override { return intensity(lambda); }
  const Vec3& position() const { return pos_; }

 private:
  Vec3 pos_;
};

// A spot light (Mitsuba 3's `spot`): intensity I(λ) inside falloffStart, falling smoothly to zero at
// the cone angle (cubic Hermite in cos θ; Mitsuba's is linear in θ). With a texture, as Mitsuba's
// `texture`, the intensity is modulated by the image cast over the cone: the local direction ω maps to
//   u = ½ + ½·ω_x/(ω_z·tan θ_c),   v = ½ + ½·ω_y/(ω_z·tan θ_c)       (Mitsuba 3, src/emitters/spot.cpp)
// in Mitsuba's look-at frame (x left, y up, z along the spot), row 0 of the image at v = 0, so the
// cone's circle is inscribed in the image, whose top-left corner lies towards −x, −y: seen from the
// light, the image is turned by 180°. I(ω, λ) = scale·I(λ)·T(u, v, λ)·falloff(ω_z), with T the
// texel's colour as an unbounded reflectance (RgbIlluminant::modulation). Emission directions are
// sampled from the image (core/projected_image.h) by luminance × falloff × cos³θ, ∝ I up to the
// texel's variation of falloff·cos³θ; without a texture, uniformly in the cone.
class SpotLight final : public Light {
 public:
  // `texture` (linear sRGB, row 0 at the top; coneDeg < 90) oriented by `up`; throws
  // std::runtime_error if it is black inside the cone.
  SpotLight(Vec3 position, Vec3 direction, float coneDeg, float falloffDeg, Spectrum intensity, float scale,
            const RgbImage* texture = nullptr, Vec3 up = Vec3(0, 1, 0));
  std::optional<LightSample> sampleLi(const Vec3& p, float lambda, Vec2 u) const override;
  float Li(const LightSample& s, float lambda) const override;
  std::optional<EmissionSample> sampleEmission(float lambda, Vec2 uPos, Vec2 uDir) const override;
  float emitted(const EmissionSample& s, float lambda) const override;
  void emissionPdfs(const Vec3& p, const Vec3& n, const Vec3& w, float& pdfPos, float& pdfDir) const override;
  bool isDelta() const override { return true; }
  float falloff(float cosTheta) const;
  float emittedTowards(float lambda, const Vec3&, const Vec3& w) const override;
  // The texture's (u, v) of a world direction leaving the light (nullopt: no texture, or outside it).
  std::optional<Vec2> directionToUv(const Vec3& w) const;

 private:
  Vec3 pos_, dir_;
  float cosTotal_, cosStart_;
  std::optional<ProjectedImage> texture_;
};

// Parallel light travelling along `direction`, irradiance E on a perpendicular plane.
class DistantLight final : public Light {
 public:
  DistantLight(Vec3 direction, Spectrum irradiance, float scale, SceneBounds bounds)
      : Light(std::move(irradiance), scale, kPi * sqr(bounds.radius)), dir_(glm::normalize(direction)), bounds_(bounds) {}
  std::optional<LightSample> sampleLi(const Vec3& p, float lambda, Vec2 u) const override;
  float Li(const LightSample& s, float lambda) const override;
  std::optional<EmissionSample> sampleEmission(float lambda, Vec2 uPos, Vec2 uDir) const override;
  float emitted(const EmissionSample& s, float lambda) const override;
  void emissionPdfs(const Vec3& p, const Vec3& n, const Vec3& w, float& pdfPos, float& pdfDir) const override;
  bool isDelta() const override { return true; }
  bool atInfinity() const override { return true; }
  float irradiance(float lambda) const { return scale_ * spectrum_(lambda); }
  const Vec3& direction() const { return dir_; }

 private:
  Vec3 dir_;
  SceneBounds bounds_;
};

// Radiance arriving from every direction at infinity. The base class is constant radiance,
// sampled uniformly over the sphere; subclasses (EnvMapLight) vary it with the direction and
// sample it by their own density: sampleLi, sampleEmission and emissionPdfs are built on
// Le, sampleDirection and pdfDirection, so every integrator sees one consistent density.
class EnvironmentLight : public Light {
 public:
  EnvironmentLight(Spectrum radiance, float scale, SceneBounds bounds)
      : Light(std::move(radiance), scale, 4.0f * kPi * kPi * sqr(bounds.radius)), bounds_(bounds) {}
  std::optional<LightSample> sampleLi(const Vec3& p, float lambda, Vec2 u) const override;
  float Li(const LightSample& s, float lambda) const override;
  std::optional<EmissionSample> sampleEmission(float lambda, Vec2 uPos, Vec2 uDir) const override;
  float emitted(const EmissionSample& s, float lambda) const override;
  void emissionPdfs(const Vec3& p, const Vec3& n, const Vec3& w, float& pdfPos, float& pdfDir) const override;
  bool atInfinity() const override { return true; }
  // Radiance at lambda arriving from direction w (unit, from the scene towards the environment).
  virtual float Le(float lambda, const Vec3& w) const { return scale_ * spectrum_(lambda); }
  // A direction towards the environment and its solid-angle density (0: none).
  virtual std::pair<Vec3, float> sampleDirection(Vec2 u) const;
  // Solid-angle density with which sampleDirection (and so sampleLi) picks w.
  virtual float pdfDirection(const Vec3& w) const;

 protected:
  SceneBounds bounds_;
};

}  // namespace kasha
