#pragma once
// Thin dielectric slab (a window pane, a soap film without interference): a sheet of index n(λ)
// so thin that light crosses it without a lateral shift. Elastic, both lobes specular, the same
// from both sides. With F = F(θ, n) the Fresnel reflectance of one face (fresnel.h), the light
// bouncing between the two faces sums to (a geometric series of internal reflections)
//   R = F + (1 − F)²·F·Σ_k F^{2k} = 2F / (1 + F),     T = 1 − R = (1 − F) / (1 + F),
// and the transmitted direction is −ω (the two refractions undo each other). Lossless.
//
// Sampling: reflect with probability R, pass straight through with probability T; these discrete
// probabilities are the direction densities, the same in both modes. Values (coefficients of the
// Dirac deltas, specular_lobe.h): R/|cos θ| and T/|cos θ|, the same in both modes (the light
// leaves into the medium it came from, so no (η_o/η_i)² factor).
#include "materials/smooth_dielectric.h"

namespace kasha {

class ThinDielectric final : public SmoothDielectric {
 public:
  using SmoothDielectric::SmoothDielectric;

  float eval(const ScatterQuery& query, const Vec3& wi, const Vec3& wo) const override;
  std::optional<DirectionSample> sampleDirection(const ScatterQuery& query, const Vec3& wKnown, Vec2 u) const override;
  float directionPdf(const ScatterQuery& query, const Vec3& wKnown, const Vec3& wSampled) const override;
  std::string describe() const override { return "thin_dielectric (" + ior_.describe() + ")"; }

  // The slab's reflectance R = 2F/(1 + F) for light arriving at |cos θ| = cosTheta.
  float reflectance(float cosTheta, float lambda) const;

 private:
  // The discrete probability of the lobe leading from wKnown to wSampled (0 if none does).
  float lobeProbability(const Vec3& wKnown, const Vec3& wSampled, float lambda) const;
};

}  // namespace kasha
