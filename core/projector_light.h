#pragma once
// A projector (Mitsuba 3's `projector`): a pinhole at `position` that projects an RGB image into
// the scene, the reciprocal of a pinhole camera. In the projector's frame (x to the left, y up,
// z forward, as Mitsuba's look-at builds it) a direction ω with ω_z > 0 passes the image plane
// z = 1 at q = ω/ω_z, which maps to the image's (u, v) with (0, 0) at its top-left corner:
//   u = (1 − q_x/tan(fov_x/2))/2,   v = (1 − q_y/tan(fov_y/2))/2,   tan(fov_y/2) = tan(fov_x/2)·H/W.
// The image is an irradiance E(u, v) on that plane, each texel's linear sRGB colour upsampled to an
// emission spectrum (core/rgb_illuminant.h). As in Mitsuba, the intensity is
//   I(ω, λ) = π·scale·E(u, v, λ) / cos³θ,                                   (cos θ = ω_z)
// so that a plane at distance z facing the projector receives π·scale·E/z² on its axis. Emission is
// sampled by choosing a texel ∝ its luminance, then a point in it: the direction's density is
// p(u, v)/(A·cos³θ) per steradian, A = 4·tan(fov_x/2)·tan(fov_y/2) the image plane's area.
#include <vector>

#include "core/distribution_2d.h"
#include "core/envmap_light.h"
#include "core/light.h"
#include "core/rgb_illuminant.h"

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
  std::optional<Vec2> directionToUv(const Vec3& w) const;

 private:
  const RgbIlluminant& texel(Vec2 uv) const;
  Vec3 pos_;
  Frame frame_;  // s = x (left), t = y (up), n = z (forward)
  float tanX_, tanY_;
  int w_, h_;
  std::vector<RgbIlluminant> texels_;
  Distribution2D distribution_;
};

}  // namespace kasha
