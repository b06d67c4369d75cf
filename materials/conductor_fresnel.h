#pragma once
// What a conductor reflects at angle θ (to the surface's or the microfacet's normal) and
// wavelength λ, by one of three laws:
//   Constant:      R(λ), the same at every angle (kasha's "mirror" given a reflectance);
//   Schlick:       F0 + (1 − F0)(1 − cos θ)⁵ from the reflectance at normal incidence F0(λ)
//                  (Schlick 1994, "An inexpensive BRDF model for physically-based rendering",
//                  eq. 15; kasha's "rough_conductor" given a reflectance);
//   ComplexIndex:  the exact Fresnel reflectance of η(λ) + i·k(λ) (fresnel.h) times a factor R(λ)
//                  (Mitsuba's specular_reflectance, or a texture), for either material given "eta".
#include "core/conductor_index.h"
#include "materials/fresnel.h"
#include "materials/surface_texture.h"

namespace kasha {

struct ConductorFresnel {
  enum class Law { Constant, Schlick, ComplexIndex };
  Law law = Law::Constant;
  HitReflectance r;                     // R, F0, or the factor on the complex index's F
  const ComplexIndex* index = nullptr;  // the material's (Law::ComplexIndex)

  float operator()(float cosTheta, float lambda) const {
    const float R = r(lambda);
    if (law == Law::Constant) return R;
    if (law == Law::Schlick) {
      const float m = 1.0f - std::clamp(cosTheta, 0.0f, 1.0f);
      return R + (1.0f - R) * (m * m) * (m * m) * m;  // Schlick 1994 eq. 15
    }
    return R * fresnelConductor(cosTheta, index->eta(lambda), index->k(lambda));
  }
  // F > 0 at some angle: where R is (Schlick's F is positive away from normal incidence always).
  bool reflects(float lambda) const { return law == Law::Schlick || r.reflects(lambda); }
};

}  // namespace kasha
