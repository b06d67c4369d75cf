#include "core/camera.h"

#include "core/sampling.h"

namespace kasha {

Camera::Camera(Vec3 position, Vec3 lookAt, Vec3 up, Vec2 halfExtent, int width, int height)
    : pos_(position), halfExtent_(halfExtent), width_(width), height_(height) {
  forward_ = glm::normalize(lookAt - position);
  right_ = glm::normalize(glm::cross(forward_, up));
  up_ = glm::cross(right_, forward_);
}

Camera::Camera(Vec3 position, Vec3 lookAt, Vec3 up, float fovYDegrees, int width, int height)
    : Camera(position, lookAt, up, Vec2(0.0f), width, height) {
  fovY_ = fovYDegrees;
  const float tanHalfY = std::tan(0.5f * fovYDegrees * kPi / 180.0f);
  halfExtent_ = Vec2(tanHalfY * float(width) / float(height), tanHalfY);
}

Camera Camera::thinLens(Vec3 position, Vec3 lookAt, Vec3 up, float fovYDegrees, int width, int height,
                        float apertureRadius, float focusDistance) {
  Camera c(position, lookAt, up, fovYDegrees, width, height);
  c.apertureRadius_ = apertureRadius;
  c.focusDistance_ = focusDistance;
  return c;
}

Camera Camera::orthographic(Vec3 position, Vec3 lookAt, Vec3 up, Vec2 filmExtent, int width, int height) {
  Camera c(position, lookAt, up, 0.5f * filmExtent, width, height);
  c.orthographic_ = true;
  return c;
}

Camera Camera::resized(int width, int height) const {
  Camera c = *this;
  c.width_ = width;
  c.height_ = height;
  c.halfExtent_.x = halfExtent_.y * float(width) / float(height);
  return c;
}

Vec3 Camera::screenPoint(Vec2 filmPos) const {
  const float sx = 2.0f * filmPos.x / float(width_) - 1.0f;
  const float sy = 1.0f - 2.0f * filmPos.y / float(height_);
  return sx * halfExtent_.x * right_ + sy * halfExtent_.y * up_;
}

std::optional<Vec2> Camera::filmPosition(const Vec3& onScreen) const {
  const float sx = glm::dot(onScreen, right_) / halfExtent_.x;
  const float sy = glm::dot(onScreen, up_) / halfExtent_.y;
  if (!(sx >= -1.0f && sx < 1.0f && sy > -1.0f && sy <= 1.0f)) return std::nullopt;
  return Vec2((sx + 1.0f) * 0.5f * float(width_), (1.0f - sy) * 0.5f * float(height_));
}

Ray Camera::generateRay(Vec2 filmPos, Vec2 lensSample) const {
  const Vec3 onScreen = screenPoint(filmPos);
  if (orthographic_) return Ray{pos_ + onScreen, forward_};
  // The ray from the lens point through the film position's point on the plane of focus (PBR4
  // eq. 5.8): every lens point sees that point, so the plane of focus is sharp. A pinhole's ray
  // leaves the position towards the image plane at distance 1.
  const Vec2 lens = apertureRadius_ * sampleConcentricDisk(lensSample);
  const Vec3 lensOffset = lens.x * right_ + lens.y * up_;
  return Ray{pos_ + lensOffset, glm::normalize(focusDistance_ * (forward_ + onScreen) - lensOffset)};
}

float Camera::rayPdf(const Ray& ray) const {
  if (orthographic_) return 1.0f / screenArea();
  // Uniform over the screen of area A at distance 1 (scaled by f on the plane of focus, seen from
  // the lens point at distance f/cosθ and angle θ): (f/cosθ)²/(cosθ·A·f²) = 1/(A·cos³θ).
  const float cosTheta = glm::dot(ray.d, forward_);
  return 1.0f / (screenArea() * cosTheta * cosTheta * cosTheta);
}

std::optional<Camera::Connection> Camera::connect(const Vec3& p, Vec2 lensSample) const {
  if (orthographic_) {
    const Vec3 fromPosition = p - pos_;
    const float depth = glm::dot(fromPosition, forward_);
    if (!(depth > 0.0f)) return std::nullopt;
    const std::optional<Vec2> pixel = filmPosition(fromPosition);
    if (!pixel) return std::nullopt;
    const float pixelArea = screenArea() / (float(width_) * float(height_));
    return Connection{*pixel, p - depth * forward_, -forward_, depth, 1.0f / pixelArea, 1.0f / screenArea()};
  }
  const Vec2 lens = apertureRadius_ * sampleConcentricDisk(lensSample);
  const Vec3 lensOffset = lens.x * right_ + lens.y * up_;
  const Vec3 toPoint = p - pos_ - lensOffset;
  const float dist2 = glm::dot(toPoint, toPoint);
  if (!(dist2 > 0.0f)) return std::nullopt;
  const float depth = glm::dot(toPoint, forward_);
  if (!(depth > 0.0f)) return std::nullopt;
  // Where the ray from the lens point through p meets the plane of focus, scaled back to the
  // screen at distance 1 (the inverse of generateRay).
  const Vec3 onFocus = lensOffset + toPoint * (focusDistance_ / depth);
  const std::optional<Vec2> pixel = filmPosition(onFocus / focusDistance_ - forward_);
  if (!pixel) return std::nullopt;
  const float dist = std::sqrt(dist2);
  const float cosTheta = depth / dist;
  const float cos3 = cosTheta * cosTheta * cosTheta;
  const float pixelArea = screenArea() / (float(width_) * float(height_));
  return Connection{*pixel, pos_ + lensOffset, -toPoint / dist, dist, 1.0f / (pixelArea * cos3 * dist2),
                    1.0f / (screenArea() * cos3)};
}

}  // namespace kasha
