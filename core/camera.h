#pragma once
// Pinhole perspective camera: vertical field of view, look-at frame, image in pixels.
#include <optional>

#include "core/ray.h"

namespace kasha {

class Camera {
 public:
  Camera() = default;
  Camera(Vec3 position, Vec3 lookAt, Vec3 up, float fovYDegrees, int width, int height);

  // Ray through the continuous film position (x right, y down, in pixels).
  Ray generateRay(Vec2 pixel) const;

  // The pinhole as a sensor for light paths. Each pixel j measures the mean radiance over the
  // directions through it, i.e. importance W_j(ω) = 1 / (A_j·cos⁴θ) for ω through pixel j, where
  // A_j is the pixel's area on the image plane at distance 1 and θ the angle to the view axis.
  struct Connection {
    Vec2 pixel;              // continuous film position hit by the direction towards the camera
    Vec3 wi;                 // unit direction from the point towards the camera
    float dist = 0.0f;
    float importance = 0.0f; // W_j·cosθ_cam / d²: the factor multiplying f·|cosθ_x| at the point
    float pdfDir = 0.0f;     // directionPdf(-wi): generateRay's density of the direction to the point
  };
  // Connects a point to the pinhole; nothing if it is behind the camera or off the film, which
  // extends `filmMargin` pixels beyond the image's edges (a reconstruction filter's reach,
  // PixelFilter::filmMargin).
  std::optional<Connection> connect(const Vec3& p, float filmMargin = 0.0f) const;
  // Solid-angle density with which generateRay (uniform over the image) produces direction d:
  // 1 / (A·cos³θ), A the whole image-plane area at distance 1; 0 off the film (as for connect).
  float directionPdf(const Vec3& d, float filmMargin = 0.0f) const;
  const Vec3& forward() const { return forward_; }
  const Vec3& up() const { return up_; }  // orthonormal to forward()
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
