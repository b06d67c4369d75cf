#pragma once
// A projector (Mitsuba 3's `projector`): a pinhole at `position` that projects an RGB image into
// the scene, the reciprocal of a pinhole camera. In the projector's frame (x to the left, y up,
// z forward, as Mitsuba's look-at builds it) the image lies on the plane z = 1 across
// tan(fov_x/2) = tanX to either side and tanY = tanX·H/W up and down, its left on the left and its
// row 0 at the top (core/projected_image.h). The image is an irradiance E(u, v) on that plane, each
// texel's linear sRGB colour upsampled to an emission spectrum (core/rgb_illuminant.h). As in
// Mitsuba, the intensity is
//   I(ω, λ) = π·scale·E(u, v, λ) / cos³θ,                                   (cos θ = ω_z)
// so that a plane at distance z facing the projector receives π·scale·E/z² on its axis. Emission is
// sampled by choosing a texel ∝ its luminance, then a point in it, so the direction's density
// p(u, v)/(A·cos³θ) is ∝ I.
#include "core/light.h"
#include "core/projected_image.h"

namespace kasha {

class ProjectorLight final : public Light {
 public:
  // `image` in linear sRGB, row 0 at the top; fovXDegrees in (0, 180). Throws std::runtime_error if
  // the image is black.
  ProjectorLight(Vec3 position, Vec3 lookAt, Vec3 up, float fovXDegrees, const RgbImage& image, float scale,
                 WavelengthRange range);
  std::optional<LightSample> sampleLi(const Vec3& p, float lambda, Vec2 u) const override;
  float Li(const LightSample& s, float lambda) const override;
  std::optional<EmissionSample> sampleEmission(float lambda, Vec2 uPos, Vec2 uDir) const override;
  float emitted(const EmissionSample& s, float lambda) const override;
  void emissionPdfs(const Vec3& p, const Vec3& n, const Vec3& w, float& pdfPos, float& pdfDir) const override;
  bool isDelta() const override { return true; }
  // I(w, λ) for a world direction w leaving the projector; 0 outside its image.
  float emittedTowards(float lambda, const Vec3&, const Vec3& w) const override;
  // The image coordinates of a world direction leaving the projector, or nullopt outside the image.
  std::optional<Vec2> directionToUv(const Vec3& w) const { return image_.directionToUv(w); }

 private:
  Vec3 pos_;
  ProjectedImage image_;
};

}  // namespace kasha
