#pragma once
// An RGB image cast from a point through the plane z = 1 of a light's frame, as Mitsuba 3's
// `projector` casts its irradiance and its `spot` its texture. A local direction ω with ω_z > 0
// meets the plane at q = ω/ω_z, which maps to the image's (u, v) ∈ [0, 1]², (0, 0) at the top-left:
//   u = (1 − q_x/tanX)/2,   v = (1 − q_y/tanY)/2,
// so the image's left is the frame's +x and its top +y. Each texel's linear sRGB colour is upsampled
// once (core/rgb_illuminant.h) and looked up without filtering. Directions are sampled by choosing a
// texel in proportion to its weight, then a uniform point in it; since dω = cos³θ·dA on the plane,
// the density per steradian is
//   p(ω) = p(u, v) / (A·cos³θ),   A = 4·tanX·tanY the image's area on the plane, cos θ = ω_z.
#include <functional>
#include <optional>
#include <vector>

#include "core/distribution_2d.h"
#include "core/rgb_illuminant.h"
#include "core/rgb_image.h"

namespace kasha {

class ProjectedImage {
 public:
  // `frame` is the light's (n forward; world = frame.toWorld(local)); `image` has row 0 at the top.
  // A texel's sampling weight is its luminance times angularWeight(ω), ω the local direction of its
  // point nearest the axis (the light's emission profile, which must not increase away from the
  // axis, so that this is the texel's largest; none: 1). Throws std::runtime_error if every weight is 0.
  ProjectedImage(const RgbImage& image, const Frame& frame, float tanX, float tanY,
                 const std::function<float(const Vec3&)>& angularWeight = {});

  // The image coordinates of a world direction, or nullopt outside the image.
  std::optional<Vec2> directionToUv(const Vec3& w) const;
  const RgbIlluminant& texel(Vec2 uv) const;

  struct Sample {
    Vec3 w;              // world direction
    Vec2 uv;
    float cosTheta = 0;  // ω_z
    float pdf = 0;       // per steradian
  };
  std::optional<Sample> sample(Vec2 u) const;
  // The density per steradian with which sample() picks the world direction w.
  float pdf(const Vec3& w) const;

  const Frame& frame() const { return frame_; }
  const std::vector<RgbIlluminant>& texels() const { return texels_; }
  float planeArea() const { return 4.0f * tanX_ * tanY_; }
  // Σ weight·ΔA over the texels: ∫ luminance·angularWeight dA over the plane at the texels' nearest
  // points, an upper estimate that steers light selection.
  double weightIntegral() const { return weightIntegral_; }

 private:
  ProjectedImage(const RgbImage& image, const Frame& frame, float tanX, float tanY, const std::vector<float>& weights);
  Frame frame_;
  float tanX_, tanY_;
  int w_, h_;
  std::vector<RgbIlluminant> texels_;
  Distribution2D distribution_;
  double weightIntegral_ = 0.0;
};

// Mitsuba's look-at frame for a light at `position` facing `lookAt`: s = left = up × forward,
// t = the frame's up = forward × left, n = forward.
Frame lookAtFrame(const Vec3& position, const Vec3& lookAt, const Vec3& up);

}  // namespace kasha
