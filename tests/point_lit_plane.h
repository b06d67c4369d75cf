#pragma once
// The closed form of scenes/validation/single_plane_point.json — a diffuse fluorescent plane under an
// isotropic point light at height h, seen straight down — exactly, and as vertex merging's disc of
// radius r blurs it (docs/bdpt-mis.md §12): the expected image of `bpm` after P passes of the
// shrinking radius. Shared by tests/statistical/test_merge_bias.cpp and bench/merge_bias/.
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

#include "integrators/progressive_schedule.h"
#include "scene/scene.h"
#include "tests/spectral_quadrature.h"

namespace kasha::test {

// The scene's geometry, with the plane at y = 0, the light above its origin and the camera looking
// straight down at the origin (validated by pointLitPlane).
struct PointLitPlane {
  double h = 0.0;       // the light's height above the plane
  double a = 0.0, b = 0.0;  // half-extents of the camera's footprint on the plane (x, z)
  double extent = 0.0;  // the plane's smaller half-extent
  Vec3 xyzPerG;         // XYZ of L_o / g, g(ρ) = h/(h² + ρ²)^{3/2} the irradiance per unit intensity
};

// Reads the scene (one point light, one Jung material, one rectangle) and checks the layout above.
inline PointLitPlane pointLitPlane(const Scene& scene) {
  const auto* light = dynamic_cast<const PointLight*>(scene.lights.at(0).get());
  const auto* m = dynamic_cast<const JungBbrrdf*>(scene.materials.at(0).get());
  const Camera& cam = scene.camera;
  if (!light || !m || scene.lights.size() != 1 || std::abs(light->position().x) > 0 ||
      std::abs(light->position().z) > 0 || std::abs(cam.position().x) > 0 || std::abs(cam.position().z) > 0 ||
      cam.forward().y > -0.9999f)
    throw std::invalid_argument("pointLitPlane: not the layout of single_plane_point.json");
  PointLitPlane p;
  p.h = light->position().y;
  // The film is parallel to the plane: its footprint is the image plane at distance 1 scaled by the
  // camera's height (vertical field of view, square pixels).
  p.b = cam.position().y * std::tan(0.5 * double(cam.fovYDegrees()) * kPi / 180.0);
  p.a = p.b * double(cam.width()) / double(cam.height());
  p.extent = 1e30;
  for (const Vec3& v : scene.shapes.at(0).positions) p.extent = std::min({p.extent, double(std::abs(v.x)), double(std::abs(v.z))});
  const Grid g(scene.range);
  p.xyzPerG = toXyz(g, singleScattering(g, *m, [&](double l) { return double(light->intensity(float(l))); }));
  return p;
}

// The mean of g over the footprint [−a, a] × [−b, b]: ∫ h/(h² + x² + z²)^{3/2} dx dz is the solid
// angle of the footprint seen from the light, 4·atan(ab / (h·√(h² + a² + b²))).
inline double footprintMeanG(const PointLitPlane& p) {
  return std::atan(p.a * p.b / (p.h * std::sqrt(p.h * p.h + p.a * p.a + p.b * p.b))) / (p.a * p.b);
}

// g averaged over a disc of radius r centred at distance s from the light's foot: in polar
// coordinates about the foot, the circle of radius ρ lies inside the disc over an angle θ(ρ) =
// 2·acos((ρ² + s² − r²)/(2ρs)) (all of it where ρ + s ≤ r). Midpoint rule in ρ.
inline double discMeanG(double h, double r, double s, int n = 2000) {
  const double lo = std::max(0.0, s - r), hi = s + r, d = (hi - lo) / n;
  double sum = 0.0;
  for (int i = 0; i < n; ++i) {
    const double rho = lo + (i + 0.5) * d;
    const double theta = rho + s <= r ? 2.0 * kPi
                                      : 2.0 * std::acos(std::clamp((rho * rho + s * s - r * r) / (2.0 * rho * s), -1.0, 1.0));
    sum += h / std::pow(h * h + rho * rho, 1.5) * rho * theta * d;
  }
  return sum / (kPi * r * r);
}

// The mean over the footprint of a radial function f(s), s the distance from the light's foot:
// (1/(ab))·∫ f(s)·s·φ(s) ds with φ(s) the angle of the quarter circle of radius s inside [0, a] × [0, b].
template <class F>
double footprintMeanRadial(const PointLitPlane& p, const F& f, int n = 400) {
  const double smax = std::sqrt(p.a * p.a + p.b * p.b), d = smax / n;
  double sum = 0.0;
  for (int i = 0; i < n; ++i) {
    const double s = (i + 0.5) * d;
    const double phi = 0.5 * kPi - std::acos(std::min(1.0, p.a / s)) - std::acos(std::min(1.0, p.b / s));
    sum += f(s) * s * std::max(0.0, phi) * d;
  }
  return sum / (p.a * p.b);
}

// The expected mean image of merges alone after `passes` passes (one sample per pixel each) with
// r_i² = progressiveRadiusSquared(r_1, α, i): each pass sees the footprint mean of the disc-blurred g
// (a uniform kernel 1/(π r²), eq. (13) of docs/bdpt-mis.md §12), and the image is their average.
// The plane must reach past the footprint by r_1, or discs would lose light off its edges.
inline Vec3 mergedMeanXyz(const PointLitPlane& p, float r1, float alpha, int passes) {
  if (p.extent < std::max(p.a, p.b) + r1) throw std::invalid_argument("mergedMeanXyz: the plane is too small for r_1");
  double sum = 0.0;
  for (int i = 1; i <= passes; ++i) {
    const double r = std::sqrt(double(progressiveRadiusSquared(r1, alpha, i)));
    sum += footprintMeanRadial(p, [&](double s) { return discMeanG(p.h, r, s); });
  }
  return p.xyzPerG * float(sum / passes);
}

// The exact (unbiased) mean image.
inline Vec3 exactMeanXyz(const PointLitPlane& p) { return p.xyzPerG * float(footprintMeanG(p)); }

}  // namespace kasha::test
