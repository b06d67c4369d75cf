#pragma once
// Shading normals (Veach 1997 §5.3) for a Bsdf whose local frame is the shading frame (z = n_s):
// integrators weight a sampled direction by f·|cos θ_s|, so the physical BSDF
//   f_s(ω_i → ω_o) = f(ω_i → ω_o)·|ω_i·n_s| / |ω_i·n_g|
// (with the geometric cosine of the sampled direction) is reproduced by f itself in Radiance
// mode (ω_i sampled) and by f·|ω_i·n_s|·|ω_o·n_g| / (|ω_i·n_g|·|ω_o·n_s|) in Importance mode (ω_o
// sampled): the adjoint of f_s is not f_s. A direction on different sides of n_s and n_g scatters
// nothing, so light cannot leak through the surface at grazing angles.
#include "core/math.h"
#include "materials/bsdf_model.h"

namespace kasha {

struct ShadingCorrection {
  Vec3 ng{0.0f, 0.0f, 1.0f};  // the geometric normal in the shading frame
  bool active = false;        // the shading normal differs from the geometric one

  ShadingCorrection() = default;
  ShadingCorrection(const Frame& geometric, const Frame& shading)
      : ng(shading.toLocal(geometric.n)), active(geometric.n != shading.n) {}

  // ω (local) lies on the same side of the shading and the geometric normal.
  bool consistent(const Vec3& w) const { return !active || w.z * glm::dot(w, ng) > 0.0f; }
  // The factor on f for an event in physical order sampled in `mode`; 0 where a direction is
  // inconsistent.
  float factor(TransportMode mode, const Vec3& wi, const Vec3& wo) const {
    if (!active) return 1.0f;
    if (!consistent(wi) || !consistent(wo)) return 0.0f;
    if (mode == TransportMode::Radiance) return 1.0f;
    const float den = std::abs(glm::dot(wi, ng)) * std::abs(wo.z);
    return den > 0.0f ? std::abs(wi.z) * std::abs(glm::dot(wo, ng)) / den : 0.0f;
  }
  // |ω·n_s| / |ω·n_g| for light arriving along ω: f times it is Veach's f_s, for estimators that
  // know the light's flux through the surface (photon density estimation) rather than a sampled
  // direction; 0 where ω is inconsistent.
  float incidentRatio(const Vec3& w) const {
    if (!active) return 1.0f;
    const float g = std::abs(glm::dot(w, ng));
    return consistent(w) && g > 0.0f ? std::abs(w.z) / g : 0.0f;
  }
};

}  // namespace kasha
