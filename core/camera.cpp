#include "core/camera.h"

#include "core/sampling.h"

namespace kasha {

Camera::Camera(Vec3 position, Vec3 lookAt, Vec3 up, float halfHeight, float aspect, int width, int height)
    : pos_(position), halfHeight_(halfHeight), aspect_(aspect), width_(width), height_(height) {
  forward_ = glm::normalize(lookAt - position);
  right_ = glm::normalize(glm::cross(forward_, up));
  up_ = glm::cross(right_, forward_);
}

Camera::Camera(Vec3 position, Vec3 lookAt, Vec3 up, float fovYDegrees, int width, int height)
    : Camera(position, lookAt, up, std::tan(0.5f * fovYDegrees * kPi / 180.0f), float(width) / float(height), width,
             height) {
  fovY_ = fovYDegrees;
}

Camera Camera::thinLens(Vec3 position, Vec3 lookAt, Vec3 up, float fovYDegrees, int width, int height,
                        float apertureRadius, float focusDistance) {
  Camera c(position, lookAt, up, fovYDegrees, width, height);
  c.apertureRadius_ = apertureRadius;
  c.focusDistance_ = focusDistance;
  return c;
}

Camera Camera::orthographic(Vec3 position, Vec3 lookAt, Vec3 up, Vec2 filmExtent, int width, int height) {
  Camera c(position, lookAt, up, 0.5f * filmExtent.y, filmExtent.x / filmExtent.y, width, height);
  c.orthographic_ = true;
  return c;
}

Camera Camera::resized(int width, int height) const {
  Camera c = *this;
  c.width_ = width;
  c.height_ = height;
  c.aspect_ = float(width) / float(height);
  return c;
}

Vec2 Camera::screenCoordinates(Vec2 filmPos) const {
  return Vec2((2.0f * filmPos.x / float(width_) - 1.0f) * halfHeight_ * aspect_,
              (1.0f - 2.0f * filmPos.y / float(height_)) * halfHeight_);
}

std::optional<Vec2> Camera::filmPosition(const Vec3& onScreen, float filmMargin) const {
  const float sx = glm::dot(onScreen, right_) / (halfHeight_ * aspect_);
  const float sy = glm::dot(onScreen, up_) / halfHeight_;
  // The margin in screen units: 2/width per pixel across, 2/height down.
  const float mx = 2.0f * filmMargin / float(width_), my = 2.0f * filmMargin / float(height_);
  if (!(sx >= -1.0f - mx && sx < 1.0f + mx && sy > -1.0f - my && sy <= 1.0f + my)) return std::nullopt;
  return Vec2((sx + 1.0f) * 0.5f * float(width_), (1.0f - sy) * 0.5f * float(height_));
}

namespace {

// A perspective camera's density per steradian of a ray at angle θ to the view axis (uniform over
// the screen of area A at distance 1, scaled by f on the plane of focus and seen from the lens point
// at distance f/cosθ and angle θ): (f/cosθ)²/(cosθ·A·f²) = 1/(A·cos³θ).
float perspectiveDensity(float screenArea, float cosTheta) { return 1.0f / (screenArea * cosTheta * cosTheta * cosTheta); }

}  // namespace

Ray Camera::generateRay(Vec2 filmPos, Vec2 lensSample) const {
  const Vec2 s = screenCoordinates(filmPos);
  if (orthographic_) return Ray{pos_ + s.x * right_ + s.y * up_, forward_};
  // The point on the image plane at distance 1; a pinhole's ray leaves the position towards it.
  const Vec3 onImagePlane = forward_ + s.x * right_ + s.y * up_;
  if (!hasLens()) return Ray{pos_, glm::normalize(onImagePlane)};
  // The ray from the lens point through the film position's point on the plane of focus (PBR4
  // eq. 5.8): every lens point sees that point, so the plane of focus is sharp.
  const Vec2 lens = apertureRadius_ * sampleConcentricDisk(lensSample);
  const Vec3 lensOffset = lens.x * right_ + lens.y * up_;
  return Ray{pos_ + lensOffset, glm::normalize(focusDistance_ * onImagePlane - lensOffset)};
}

float Camera::rayPdf(const Ray& ray, float filmMargin) const {
  if (orthographic_) return filmPosition(ray.o - pos_, filmMargin) ? 1.0f / screenArea() : 0.0f;
  const float cosTheta = glm::dot(ray.d, forward_);
  if (cosTheta <= 0.0f) return 0.0f;
  // The ray's point on the plane of focus, scaled back to distance 1: d/cosθ + (lens offset)/f.
  const Vec3 onScreen = ray.d / cosTheta + (ray.o - pos_) / focusDistance_;
  if (!filmPosition(onScreen, filmMargin)) return 0.0f;
  return perspectiveDensity(screenArea(), cosTheta);
}

std::optional<Camera::Connection> Camera::connect(const Vec3& p, Vec2 lensSample, float filmMargin) const {
  const float pixelArea = screenArea() / (float(width_) * float(height_));
  if (orthographic_) {
    const Vec3 fromPosition = p - pos_;
    const float depth = glm::dot(fromPosition, forward_);
    if (!(depth > 0.0f)) return std::nullopt;
    const std::optional<Vec2> pixel = filmPosition(fromPosition, filmMargin);
    if (!pixel) return std::nullopt;
    return Connection{*pixel, p - depth * forward_, -forward_, depth, 1.0f / pixelArea, 1.0f / screenArea()};
  }
  Vec3 lensOffset(0.0f);
  if (hasLens()) {
    const Vec2 lens = apertureRadius_ * sampleConcentricDisk(lensSample);
    lensOffset = lens.x * right_ + lens.y * up_;
  }
  const Vec3 lensPoint = pos_ + lensOffset;
  Vec3 wi = lensPoint - p;
  const float dist2 = glm::dot(wi, wi);
  if (!(dist2 > 0.0f)) return std::nullopt;
  const float dist = std::sqrt(dist2);
  wi /= dist;
  const float cosTheta = -glm::dot(wi, forward_);
  if (cosTheta <= 0.0f) return std::nullopt;
  // Where the ray from the lens point through p meets the plane of focus, scaled back to the
  // screen at distance 1 (the inverse of generateRay): −wi/cosθ + (lens offset)/f.
  const std::optional<Vec2> pixel = filmPosition(-wi / cosTheta + lensOffset / focusDistance_, filmMargin);
  if (!pixel) return std::nullopt;
  const float cos2 = cosTheta * cosTheta;
  // W_j·A_lens·cosθ/d² with W_j = 1/(A_lens·A_j·cos⁴θ)
  return Connection{*pixel, lensPoint, wi, dist, 1.0f / (pixelArea * cos2 * cosTheta * dist2),
                    perspectiveDensity(screenArea(), cosTheta)};
}

}  // namespace kasha
