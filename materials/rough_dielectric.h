#pragma once
// Rough dielectric interface (frosted glass): GGX microfacet reflection and refraction (ggx.h),
// elastic, with the index n(λ) (ior.h) inside relative to the vacuum outside, outside being the
// side the geometric normal points to (local z > 0), as for the smooth Dielectric.
//
// With η_i, η_o the indices on the sides of ω_i and ω_o, F the dielectric Fresnel (fresnel.h) at
// the microfacet, and G = G1(ω_i)·G1(ω_o):
//   reflection  f = F(|ω_i·h_r|)·D(h_r)·G / (4|cos θ_i||cos θ_o|)                       Walter07 eq. 20
//   refraction  f = |ω_i·h_t||ω_o·h_t| / (|cos θ_i||cos θ_o|) ·
//                   η_o²·(1 − F(|ω_i·h_t|))·D(h_t)·G / (η_i(ω_i·h_t) + η_o(ω_o·h_t))²      Walter07 eq. 21
// with h_r, h_t the half vectors of ggx.h (Walter07 eqs. 13, 16). This is the physical BSDF of
// light arriving along ω_i and leaving along ω_o, so, unlike the Dirac coefficients of the smooth
// Dielectric, it is one value for both transport modes (material.h). It obeys Veach's relation
// for refraction, f(ω_i→ω_o)/η_o² = f(ω_o→ω_i)/η_i² (Veach97 §5.2), and the η² radiance scaling
// shows in one mode only, through the sampling densities: the weights f·|cos θ_sampled|/pdf are
//   Importance (ω_o sampled)  reflection F·G1(ω_o)/P_r,  refraction (1 − F)·G1(ω_o)/(1 − P_r)
//   Radiance   (ω_i sampled)  reflection F·G1(ω_i)/P_r,  refraction (η_o/η_i)²·(1 − F)·G1(ω_i)/(1 − P_r)
// i.e. the smooth dielectric's weights (dielectric.h) times the masking of the sampled direction.
//
// Sampling from the known direction ω_k: choose reflection with probability
//   P_r(ω_k) = clamp(F(|cos θ_k|, η), 0.1, 0.9),
// the Fresnel reflectance of the macro surface kept away from 0 and 1, since microfacets reflect
// and refract at every angle (even beyond the macro surface's critical angle); then a visible
// normal m from ω_k (Heitz18) and ω_k mirrored about m or refracted through it (Walter07 eqs.
// 39–40). The lobe is chosen before m because the directional stage has two random numbers; the
// choice therefore cannot follow the facet's own F, but every direction with f > 0 keeps a
// positive density. Densities (Walter07 eqs. 14, 17):
//   reflection  P_r·D_k(h_r) / (4|ω_k·h_r|)
//   refraction  (1 − P_r)·D_k(h_t)·η_s²|ω_s·h_t| / (η_k(ω_k·h_t) + η_s(ω_s·h_t))²
// with ω_s the sampled direction. A refraction blocked by total internal reflection at m, or a
// direction that ends on the wrong side of the macro surface, is a failed sample (f = 0 there).
//
// Texture (materials/surface_texture.h): "alpha_texture" on both α or one each (clamped to kMinAlpha).
#include "materials/elastic_model.h"
#include "materials/ggx.h"
#include "materials/ior.h"
#include "materials/surface_texture.h"
#include "materials/textured_material.h"

namespace kasha {

// The model at one hit.
class RoughDielectricModel : public ElasticModel {
 public:
  RoughDielectricModel(Ior ior, Ggx ggx) : ior_(std::move(ior)), ggx_(ggx) {}

  float eval(const ScatterQuery& query, const Vec3& wi, const Vec3& wo) const override;
  std::optional<DirectionSample> sampleDirection(const ScatterQuery& query, const Vec3& wKnown, Vec2 u) const override;
  float directionPdf(const ScatterQuery& query, const Vec3& wKnown, const Vec3& wSampled) const override;
  // Dispersion changes the refracted direction and the Fresnel choice between the lobes.
  BsdfFlags flags() const override { return flagIf(ior_.dispersive(), BsdfFlags::WavelengthDependentDirection); }

  const Ior& ior() const { return ior_; }
  const Ggx& ggx() const { return ggx_; }
  // Index of refraction on the side of w (1 outside, n(λ) inside).
  float sideIndex(const Vec3& w, float lambda) const { return w.z > 0.0f ? 1.0f : ior_(lambda); }
  // Probability of choosing reflection when sampling from w.
  float reflectProbability(const Vec3& w, float lambda) const;

 private:
  // Unnormalised: the density of the direction given the lobe, times its probability, or 0.
  float density(const Vec3& wKnown, const Vec3& wSampled, float lambda) const;

  Ior ior_;
  Ggx ggx_;
};

class RoughDielectric final : public TexturedMaterial<RoughDielectricModel> {
 public:
  // Throws std::invalid_argument "ior: ..." if n(λ) is invalid (checkIor) or closer to 1 than
  // 1.001 anywhere in the range (index-matched refraction is a Dirac delta straight through, which
  // the generalised half vector cannot describe), or "alpha: ..." (checkedGgx).
  RoughDielectric(Ior ior, float alphaX, float alphaY, WavelengthRange range, AlphaTexture alphaTexture = {});
  std::optional<FluorophoreSpectra> fluorophore() const override { return std::nullopt; }
  std::string describe() const override { return "rough_dielectric (" + ior().describe() + ")"; }
  bool textured() const override { return alphaTexture_.any(); }
  std::vector<const Texture*> textures() const override { return setTextures(alphaTexture_.x, alphaTexture_.y); }

 private:
  RoughDielectricModel modelAt(const TexturePoint& p) const override {
    return RoughDielectricModel(ior(), texturedGgx(ggx(), alphaTexture_, p));
  }
  AlphaTexture alphaTexture_;
};

}  // namespace kasha
