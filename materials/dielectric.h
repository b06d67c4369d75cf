#pragma once
// Smooth dielectric interface (glass): Fresnel reflection and refraction, elastic, both lobes
// specular. The index n(λ) (ior.h) is that of the inside relative to the outside (vacuum); the
// outside is the side the geometric normal points to (local z > 0), so a sphere is glass inside.
// A dispersive index refracts each wavelength into its own direction.
//
// Sampling: from the known direction, reflect with probability F (fresnel.h) and refract with
// probability 1 − F; these discrete probabilities are the direction densities (material.h), the
// same in both modes and in reverse since F is the same from both sides of an event.
//
// Values (coefficients of the Dirac deltas in the solid angle of the sampled direction):
//   reflection   f = F / |cos θ_sampled|                                    both modes
//   refraction   f = (η_o/η_i)²·(1 − F) / |cos θ_i|    Radiance (ω_i sampled)
//                f = (1 − F) / |cos θ_o|               Importance (ω_o sampled)
// with η_i, η_o the indices on the sides of ω_i and ω_o. Radiance crossing into a medium of
// higher index is compressed into a smaller solid angle and grows by (η_o/η_i)², while the power
// a particle carries only loses the reflected part (Veach97 §5.2; pbrt-v4's TransportMode). Both
// values describe one physical BSDF: refraction maps dω_o = (η_i/η_o)²·|cos θ_i|/|cos θ_o|·dω_i,
// which turns one coefficient into the other, and they satisfy Veach's relation for refraction
// f(ω_i→ω_o)/η_o² = f(ω_o→ω_i)/η_i² (both deltas in the same direction's solid angle). So the
// path weight f·|cos θ_sampled|/pdf is 1 for every event except a refraction in Radiance mode,
// where it is (η_o/η_i)².
#include "materials/smooth_dielectric.h"

namespace kasha {

class Dielectric final : public SmoothDielectric {
 public:
  using SmoothDielectric::SmoothDielectric;

  float eval(const ScatterQuery& query, const Vec3& wi, const Vec3& wo) const override;
  std::optional<DirectionSample> sampleDirection(const ScatterQuery& query, const Vec3& wKnown, Vec2 u) const override;
  float directionPdf(const ScatterQuery& query, const Vec3& wKnown, const Vec3& wSampled) const override;
  std::string describe() const override { return "dielectric (" + ior_.describe() + ")"; }

  // η_far/η_w: the index on the far side of the surface from w over the index on w's side.
  float relativeEta(const Vec3& w, float lambda) const;

 private:
  // Which lobe leads from wKnown to wSampled at λ, and its discrete probability.
  struct Match {
    bool reflect = false, refract = false;
    float prob = 0.0f;
  };
  Match match(const Vec3& wKnown, const Vec3& wSampled, float lambda) const;
};

}  // namespace kasha
