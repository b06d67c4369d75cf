#include "core/camera.h"

namespace kasha {

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
