#pragma once
// Pinhole perspective camera: vertical field of view, look-at frame, image in pixels.
#include "core/ray.h"

namespace kasha {

class Camera {
 public:
  Camera() = default;
  Camera(Vec3 position, Vec3 lookAt, Vec3 up, float fovYDegrees, int width, int height);

  // Ray through the continuous film position (x right, y down, in pixels).
  Ray generateRay(Vec2 pixel) const;
  int width() const { return width_; }
  int height() const { return height_; }
  const Vec3& position() const { return pos_; }
  float fovYDegrees() const { return fovY_; }

 private:
  Vec3 pos_{0.0f}, forward_{0, 0, 1}, right_{1, 0, 0}, up_{0, 1, 0};
  float fovY_ = 40.0f, tanHalfY_ = 0.36f, aspect_ = 1.0f;
  int width_ = 1, height_ = 1;
};

}  // namespace kasha
