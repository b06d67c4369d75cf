#include "core/envmap_light.h"

#include "core/exr_input.h"


#include "core/memory_budget.h"

#include <ImfArray.h>
#include <ImfRgbaFile.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace kasha {
namespace {

// The light's mean radiance over the sphere, Σ_t L_t(λ)·ΔΩ_t / 4π, every 5 nm over the range:
// the spectrum that, times the environment's 4π²r², is its power (LightSelector).
// The mean radiance over the sphere: texels weighted by their solid angle ΔΩ = (2π/W)·(cos θ_top − cos θ_bottom).
Spectrum meanRadiance(const std::vector<RgbIlluminant>& texels, int w, int h, WavelengthRange range) {
  std::vector<float> solidAngle(texels.size());
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      solidAngle[size_t(y) * size_t(w) + size_t(x)] =
          2.0f * kPi / float(w) * (std::cos(kPi * float(y) / float(h)) - std::cos(kPi * float(y + 1) / float(h)));
  return meanTexelSpectrum(texels, solidAngle, 4.0 * M_PI, range);  // Σ ΔΩ = 4π
}

// Sampling weights: luminance (Rec. 709 / sRGB Y) times sin θ at the row's centre.
std::vector<float> weights(const RgbImage& image) {
  std::vector<float> w(image.pixels.size());
  for (int y = 0; y < image.height; ++y) {
    const float sinTheta = std::sin(kPi * (float(y) + 0.5f) / float(image.height));
    for (int x = 0; x < image.width; ++x) {
      const Vec3& p = image.pixels[size_t(y) * size_t(image.width) + size_t(x)];
      w[size_t(y) * size_t(image.width) + size_t(x)] = luminance(p) * sinTheta;
    }
  }
  return w;
}

}  // namespace

RgbImage loadEnvironmentImage(const std::string& path, uint64_t memoryLimit) {
  RgbImage img;
  try {
    // Read whole through core/input_file.h (its rules, and the digest of a scene's inputs) and
    // decoded from memory: OpenEXR never opens the path itself.
    ExrInput in(path, "environment map");
    const std::unique_ptr<Imf::IStream> stream = in.stream();
    Imf::RgbaInputFile file(*stream);
    const Imath::Box2i dw = file.dataWindow();
    const int64_t w = int64_t(in.width()), h = int64_t(in.height());
    requireMemory(saturatingMul(uint64_t(w) * uint64_t(h), kEmittingImageBytesPerPixel),
                  "'" + path + "' (" + std::to_string(w) + " x " + std::to_string(h) + "): the environment light",
                  memoryLimit);
    Imf::Array2D<Imf::Rgba> px(h, w);
    file.setFrameBuffer(&px[0][0] - dw.min.x - dw.min.y * w, 1, size_t(w));
    file.readPixels(dw.min.y, dw.max.y);
    img.width = int(w);
    img.height = int(h);
    img.pixels.reserve(size_t(w * h));
    for (int64_t y = 0; y < h; ++y)
      for (int64_t x = 0; x < w; ++x) {
        const Imf::Rgba& p = px[y][x];
        const Vec3 c(float(p.r), float(p.g), float(p.b));
        if (!(std::isfinite(c.x) && std::isfinite(c.y) && std::isfinite(c.z)) || c.x < 0.0f || c.y < 0.0f || c.z < 0.0f)
          throw std::runtime_error("'" + path + "': pixel (" + std::to_string(x) + ", " + std::to_string(y) +
                                   ") is negative or not finite");
        img.pixels.push_back(c);
      }
  } catch (const std::runtime_error&) {
    throw;
  } catch (const std::exception& e) {  // OpenEXR's Iex exceptions
    throw std::runtime_error("'" + path + "': cannot read it as OpenEXR: " + e.what());
  }
  return img;
}

EnvMapLight::EnvMapLight(const RgbImage& image, const glm::mat4& toWorld, float scale, SceneBounds bounds,
                         WavelengthRange range)
    : EnvironmentLight(Spectrum::constant(0.0f), scale, bounds),
      w_(image.width),
      h_(image.height),
      texels_(upsampleTexels(image)),
      distribution_(weights(image), image.width, image.height) {
  if (distribution_.empty()) throw std::runtime_error("the environment image is black");
  const glm::mat3 m(toWorld);
  const float s = std::cbrt(glm::determinant(m));
  toWorld_ = m / s;
  toLocal_ = glm::transpose(toWorld_);
  spectrum_ = meanRadiance(texels_, w_, h_, range);
}

Vec2 EnvMapLight::directionToUv(const Vec3& w) const {
  const Vec3 d = toLocal_ * w;
  float u = std::atan2(d.x, -d.z) / (2.0f * kPi);
  if (u < 0.0f) u += 1.0f;
  const float v = std::atan2(std::sqrt(d.x * d.x + d.z * d.z), d.y) / kPi;  // θ/π, well conditioned at the poles
  return {std::min(u, 0x1.fffffep-1f), std::min(v, 0x1.fffffep-1f)};
}

Vec3 EnvMapLight::uvToDirection(Vec2 uv) const {
  const float phi = 2.0f * kPi * uv.x, theta = kPi * uv.y;
  const float st = std::sin(theta);
  return glm::normalize(toWorld_ * Vec3(st * std::sin(phi), std::cos(theta), -st * std::cos(phi)));
}

size_t EnvMapLight::texel(Vec2 uv) const {
  const int x = cellIndex(uv.x, w_), y = cellIndex(uv.y, h_);
  return size_t(y) * size_t(w_) + size_t(x);
}

float EnvMapLight::Le(float lambda, const Vec3& w) const { return scale_ * texels_[texel(directionToUv(w))](lambda); }

std::pair<Vec3, float> EnvMapLight::sampleDirection(Vec2 u) const {
  const Distribution2D::Sample s = distribution_.sample(u);
  if (!(s.pdf > 0.0f)) return {Vec3(0.0f), 0.0f};
  // The density of the direction as pdfDirection computes it, so that MIS weights never see two
  // values for one direction (they differ only by rounding, near the poles).
  const Vec3 w = uvToDirection(s.uv);
  return {w, pdfDirection(w)};
}

float EnvMapLight::pdfDirection(const Vec3& w) const {
  const Vec3 d = toLocal_ * w;
  const float sinTheta = std::sqrt(d.x * d.x + d.z * d.z) / glm::length(d);
  if (!(sinTheta > 0.0f)) return 0.0f;
  return distribution_.pdf(directionToUv(w)) / (2.0f * kPi * kPi * sinTheta);
}

}  // namespace kasha
