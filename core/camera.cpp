#include "core/camera.h"

namespace kasha {
namespace {

// generateRay's density per steradian of a direction at angle θ to the view axis (uniform over
// the image plane of area A at distance 1): 1 / (A·cos³θ).
float directionDensity(float planeArea, float cosTheta) { return 1.0f / (planeArea * cosTheta * cosTheta * cosTheta); }

}  // namespace

Camera::Camera(Vec3 position, Vec3 lookAt, Vec3 up, float fovYDegrees, int width, int height)
    : pos_(position), fovY_(fovYDegrees), width_(width), height_(height) {
  forward_ = glm::normalize(lookAt - position);
  right_ = glm::normalize(glm::cross(forward_, up));
  up_ = glm::cross(right_, forward_);
  tanHalfY_ = std::tan(0.5f * fovYDegrees * kPi / 180.0f);
  aspect_ = float(width) / float(height);
}

Ray Camera::generateRay(Vec2 pixel) const {
  const float sx = (2.0f * pixel.x / float(width_) - 1.0f) * tanHalfY_ * aspect_;
  const float sy = (1.0f - 2.0f * pixel.y / float(height_)) * tanHalfY_;
  return Ray{pos_, glm::normalize(forward_ + sx * right_ + sy * up_)};
}

}  // namespace kasha

namespace kasha {

std::optional<Camera::Connection> Camera::connect(const Vec3& p, float filmMargin) const {
  Vec3 d = pos_ - p;
  const float dist2 = glm::dot(d, d);
  if (!(dist2 > 0.0f)) return std::nullopt;
  const float dist = std::sqrt(dist2);
  d /= dist;
  const Vec3 toPoint = -d;
  const float cosTheta = glm::dot(toPoint, forward_);
  if (cosTheta <= 0.0f) return std::nullopt;
  // Image-plane coordinates at distance 1 along the view axis.
  const Vec3 onPlane = toPoint / cosTheta;
  const float sx = glm::dot(onPlane, right_) / (tanHalfY_ * aspect_);
  const float sy = glm::dot(onPlane, up_) / tanHalfY_;
  // The margin in image-plane units: 2/width per pixel across, 2/height down.
  const float mx = 2.0f * filmMargin / float(width_), my = 2.0f * filmMargin / float(height_);
  if (sx < -1.0f - mx || sx >= 1.0f + mx || sy <= -1.0f - my || sy > 1.0f + my) return std::nullopt;
  const Vec2 pixel((sx + 1.0f) * 0.5f * float(width_), (1.0f - sy) * 0.5f * float(height_));
  const float planeArea = 4.0f * tanHalfY_ * tanHalfY_ * aspect_;
  const float pixelArea = planeArea / (float(width_) * float(height_));
  const float cos2 = cosTheta * cosTheta;
  // W_j·cosθ / d² with W_j = 1/(A_j·cos⁴θ)
  return Connection{pixel, d, dist, 1.0f / (pixelArea * cos2 * cosTheta * dist2), directionDensity(planeArea, cosTheta)};
}

float Camera::directionPdf(const Vec3& d, float filmMargin) const {
  const float cosTheta = glm::dot(d, forward_);
  if (cosTheta <= 0.0f) return 0.0f;
  const Vec3 onPlane = d / cosTheta;
  const float sx = glm::dot(onPlane, right_) / (tanHalfY_ * aspect_);
  const float sy = glm::dot(onPlane, up_) / tanHalfY_;
  const float mx = 2.0f * filmMargin / float(width_), my = 2.0f * filmMargin / float(height_);
  if (sx < -1.0f - mx || sx > 1.0f + mx || sy < -1.0f - my || sy > 1.0f + my) return 0.0f;
  return directionDensity(4.0f * tanHalfY_ * tanHalfY_ * aspect_, cosTheta);
}

}  // namespace kasha
