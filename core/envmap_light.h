#pragma once
// An environment light from an equirectangular (latitude-longitude) RGB image, Mitsuba's
// `envmap`: the direction d = (sinθ·sinφ, cosθ, −sinθ·cosφ) in the light's frame (+y up) sees
// pixel (u·W, v·H) with u = φ/2π, v = θ/π (row 0 at the top, θ = 0). Each texel's colour is
// upsampled to an emission spectrum (core/rgb_illuminant.h), constant over the texel (nearest
// lookup). Directions are importance-sampled from a piecewise-constant density over the image
// ∝ luminance·sinθ (pbrt-v4 §12.5.2), whose solid-angle density is p(u, v)/(2π²·sinθ).
#include <glm/mat3x3.hpp>
#include <glm/mat4x4.hpp>

#include <string>
#include <vector>

#include "core/distribution_2d.h"
#include "core/light.h"
#include "core/rgb_illuminant.h"
#include "core/rgb_image.h"

namespace kasha {


// Reads an OpenEXR image's R, G, B (missing channels are 0). Throws std::runtime_error naming
// the file for an unreadable file, a negative or non-finite value (with its pixel), or an image
// whose kEmittingImageBytesPerPixel per pixel exceed `memoryLimit` (checked from the header, before
// decoding).
RgbImage loadEnvironmentImage(const std::string& path, uint64_t memoryLimit);

class EnvMapLight final : public EnvironmentLight {
 public:
  // `toWorld`'s 3×3 part must be a rotation times a positive uniform scale (checked by the
  // caller); `range` is the scene's wavelength range (for the light's mean spectrum). Throws
  // std::runtime_error if the image is black.
  EnvMapLight(const RgbImage& image, const glm::mat4& toWorld, float scale, SceneBounds bounds, WavelengthRange range);

  float Le(float lambda, const Vec3& w) const override;
  std::pair<Vec3, float> sampleDirection(Vec2 u) const override;
  float pdfDirection(const Vec3& w) const override;

  // The image coordinates (u, v) ∈ [0, 1)² of a world direction, and back.
  Vec2 directionToUv(const Vec3& w) const;
  Vec3 uvToDirection(Vec2 uv) const;

 private:
  size_t texel(Vec2 uv) const;
  int w_, h_;
  std::vector<RgbIlluminant> texels_;
  Distribution2D distribution_;
  glm::mat3 toWorld_, toLocal_;
};

}  // namespace kasha
