#include "core/projected_image.h"

#include <algorithm>
#include <stdexcept>

namespace kasha {
namespace {

// The local direction through the image point (u, v) (the header's mapping, inverted).
Vec3 uvToLocal(Vec2 uv, float tanX, float tanY) {
  return glm::normalize(Vec3((1.0f - 2.0f * uv.x) * tanX, (1.0f - 2.0f * uv.y) * tanY, 1.0f));
}

// Luminance × angularWeight at each texel's point nearest the axis (u, v) = (½, ½), row-major.
std::vector<float> texelWeights(const RgbImage& image, float tanX, float tanY,
                                const std::function<float(const Vec3&)>& angularWeight) {
  std::vector<float> w = texelLuminances(image);
  if (!angularWeight) return w;
  const float du = 1.0f / float(image.width), dv = 1.0f / float(image.height);
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) {
      const Vec2 nearest(std::clamp(0.5f, float(x) * du, float(x + 1) * du), std::clamp(0.5f, float(y) * dv, float(y + 1) * dv));
      w[size_t(y) * size_t(image.width) + size_t(x)] *= angularWeight(uvToLocal(nearest, tanX, tanY));
    }
  return w;
}

}  // namespace

Frame lookAtFrame(const Vec3& position, const Vec3& lookAt, const Vec3& up) {
  const Vec3 z = glm::normalize(lookAt - position);
  const Vec3 x = glm::normalize(glm::cross(up, z));
  return Frame{x, glm::cross(z, x), z};
}

ProjectedImage::ProjectedImage(const RgbImage& image, const Frame& frame, float tanX, float tanY,
                               const std::function<float(const Vec3&)>& angularWeight)
    : ProjectedImage(image, frame, tanX, tanY, texelWeights(image, tanX, tanY, angularWeight)) {}

ProjectedImage::ProjectedImage(const RgbImage& image, const Frame& frame, float tanX, float tanY,
                               const std::vector<float>& weights)
    : frame_(frame),
      tanX_(tanX),
      tanY_(tanY),
      w_(image.width),
      h_(image.height),
      texels_(upsampleTexels(image)),
      distribution_(weights, image.width, image.height) {
  if (distribution_.empty()) throw std::runtime_error("the image is black where it is cast");
  double sum = 0.0;
  for (float x : weights) sum += double(x);
  weightIntegral_ = sum * double(planeArea()) / double(weights.size());
}

std::optional<Vec2> ProjectedImage::directionToUv(const Vec3& w) const {
  const Vec3 local = frame_.toLocal(w);
  if (!(local.z > 0.0f)) return std::nullopt;
  const Vec2 uv(0.5f * (1.0f - local.x / (local.z * tanX_)), 0.5f * (1.0f - local.y / (local.z * tanY_)));
  if (!(uv.x >= 0.0f && uv.x <= 1.0f && uv.y >= 0.0f && uv.y <= 1.0f)) return std::nullopt;
  return uv;
}

const RgbIlluminant& ProjectedImage::texel(Vec2 uv) const {
  return texels_[size_t(cellIndex(uv.y, h_)) * size_t(w_) + size_t(cellIndex(uv.x, w_))];
}

std::optional<ProjectedImage::Sample> ProjectedImage::sample(Vec2 u) const {
  const Distribution2D::Sample s = distribution_.sample(u);
  if (!(s.pdf > 0.0f)) return std::nullopt;
  const Vec3 local = uvToLocal(s.uv, tanX_, tanY_);
  return Sample{frame_.toWorld(local), s.uv, local.z, s.pdf / (planeArea() * local.z * local.z * local.z)};
}

float ProjectedImage::pdf(const Vec3& w) const {
  const std::optional<Vec2> uv = directionToUv(w);
  if (!uv) return 0.0f;
  const float c = glm::dot(w, frame_.n);
  return distribution_.pdf(*uv) / (planeArea() * c * c * c);
}

}  // namespace kasha
