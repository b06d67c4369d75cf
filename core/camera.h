#pragma once
// The camera: a look-at frame, an image of width × height pixels, and one of three projections.
//   - pinhole: perspective through a point, with a vertical field of view;
//   - thin lens: perspective through a disk of radius r on the view plane, focused on the plane at
//     distance f along the view axis (PBR4 §5.2.3; Mitsuba 3 docs: thinlens); a pinhole is a thin
//     lens with r = 0;
//   - orthographic: rays along the view axis from a rectangle of the view plane of given world
//     extent (PBR4 §5.2.1; Mitsuba 3 docs: orthographic).
// Film coordinates are pixels, x right and y down; the screen maps them to s ∈ [−1, 1]², which the
// screen's half-extents scale: tan of the half angles on the image plane at distance 1
// (perspective), world lengths on the view plane (orthographic).
#include <optional>

#include "core/ray.h"

namespace kasha {

class Camera {
 public:
  Camera() = default;
  // A pinhole.
  Camera(Vec3 position, Vec3 lookAt, Vec3 up, float fovYDegrees, int width, int height);
  static Camera thinLens(Vec3 position, Vec3 lookAt, Vec3 up, float fovYDegrees, int width, int height,
                         float apertureRadius, float focusDistance);
  // filmExtent: the film's width and height in world units, centred on `position`.
  static Camera orthographic(Vec3 position, Vec3 lookAt, Vec3 up, Vec2 filmExtent, int width, int height);

  // The same camera at another resolution: the vertical extent (field of view, or the orthographic
  // film's height) kept, the horizontal one following the new aspect ratio.
  Camera resized(int width, int height) const;

  // The ray through the continuous film position (pixels), from the lens point that lensSample
  // ([0,1)², concentric map to the disk) picks; the pinhole and the orthographic camera ignore it.
  Ray generateRay(Vec2 filmPos, Vec2 lensSample) const;

  // The camera as a sensor for light paths. Pixel j measures the mean radiance over the rays
  // through it: importance W_j = 1/(A_lens·A_j·cos⁴θ) for a perspective camera (A_j the pixel's area
  // on the image plane at distance 1, θ the ray's angle to the view axis, A_lens = πr², a delta of
  // the lens position for the pinhole), and W_j = δ(ω − forward)/A_j for the orthographic camera
  // (A_j the pixel's world area) (PBR4 §5.4.1 and §16.1.1).
  struct Connection {
    Vec2 pixel;              // continuous film position of the ray from lensPoint through the point
    Vec3 lensPoint;          // where that ray starts: the lens sample, or the point's projection (orthographic)
    Vec3 wi;                 // unit direction from the point towards lensPoint
    float dist = 0.0f;
    // The factor multiplying f·|cosθ_x| at the point, the lens point's density divided out:
    // W_j·A_lens·cosθ/d² = 1/(A_j·cos³θ·d²) (perspective) or 1/A_j (orthographic: the projection
    // onto the film turns dA(film) into |cosθ_x|·dA(x), with no 1/d²).
    float importance = 0.0f;
    float pdfRay = 0.0f;     // rayPdf of the ray from lensPoint towards the point
  };
  // Connects a point to the camera through the lens point lensSample picks (thin lens; the pinhole
  // and the orthographic camera have one lens point per point); nothing if the point is behind the
  // view plane or the ray misses the film, which extends `filmMargin` pixels beyond the image's
  // edges (a reconstruction filter's reach, PixelFilter::filmMargin).
  std::optional<Connection> connect(const Vec3& p, Vec2 lensSample, float filmMargin = 0.0f) const;
  // The density with which generateRay (uniform over the image) produces a ray it returned, given
  // its origin: per steradian for a perspective camera, 1/(A·cos³θ) with A the screen's area at
  // distance 1 (the lens point's density, the same in every way of sampling it, left out); per unit
  // area across the rays for the orthographic camera, whose direction is fixed: 1/A, A the film's
  // world area. 0 off the film (as for connect).
  float rayPdf(const Ray& ray, float filmMargin = 0.0f) const;

  // Whether the camera has a lens to sample (a thin lens of aperture > 0): only then do ray
  // generation and connections use lens numbers.
  bool hasLens() const { return !orthographic_ && apertureRadius_ > 0.0f; }
  // The lens numbers of one ray or connection: two from rng with a lens, none without (the
  // sampler's dimensions then stay those of a camera without lens numbers).
  template <class Rng>
  Vec2 sampleLens(Rng& rng) const {
    return hasLens() ? rng.uniform2() : Vec2(0.5f);
  }
  // Whether every ray has the view axis as direction (orthographic): densities of the points the
  // rays reach are then per unit area across them (times |cosθ| there, no 1/d²).
  bool parallelRays() const { return orthographic_; }
  bool pinhole() const { return !orthographic_ && apertureRadius_ == 0.0f; }
  const Vec3& forward() const { return forward_; }
  const Vec3& up() const { return up_; }  // orthonormal to forward()
  int width() const { return width_; }
  int height() const { return height_; }
  const Vec3& position() const { return pos_; }
  float fovYDegrees() const { return fovY_; }  // perspective cameras
  float apertureRadius() const { return apertureRadius_; }
  float focusDistance() const { return focusDistance_; }
  Vec2 filmExtent() const { return 2.0f * Vec2(halfHeight_ * aspect_, halfHeight_); }  // orthographic: world units

 private:
  Camera(Vec3 position, Vec3 lookAt, Vec3 up, float halfHeight, float aspect, int width, int height);
  // The film position's screen coordinates s·h: along right and up, relative to the position.
  Vec2 screenCoordinates(Vec2 filmPos) const;
  // The film position of a screen point (relative to the position; its part along forward
  // ignored), if it lies on the film widened by filmMargin pixels.
  std::optional<Vec2> filmPosition(const Vec3& onScreen, float filmMargin) const;
  float screenArea() const { return 4.0f * halfHeight_ * halfHeight_ * aspect_; }

  Vec3 pos_{0.0f}, forward_{0, 0, 1}, right_{1, 0, 0}, up_{0, 1, 0};
  // The screen's half-height h.y (tan of the half field of view, or world units) and its width
  // over its height, h.x = h.y·aspect.
  float halfHeight_ = 0.36f, aspect_ = 1.0f;
  float fovY_ = 40.0f;
  bool orthographic_ = false;
  float apertureRadius_ = 0.0f, focusDistance_ = 1.0f;
  int width_ = 1, height_ = 1;
};

}  // namespace kasha
