#pragma once
// The GGX (Trowbridge–Reitz) microfacet distribution, optionally anisotropic, with Smith masking
// and sampling of the distribution of visible normals, in the local frame of the macro normal
// (z up). Microfacet normals m always point to z > 0; a direction below the surface sees the
// back of the same facets (everything here depends on |w.z| and on |w·m| only through the sign
// conventions stated per function).
//
// Walter07: Walter, Marschner, Li & Torrance, "Microfacet Models for Refraction through Rough
// Surfaces", EGSR 2007. Heitz14: Heitz, "Understanding the Masking-Shadowing Function in
// Microfacet-Based BRDFs", JCGT 3(2), 2014.
//
//   D(m)    = 1 / (π α_x α_y (m_x²/α_x² + m_y²/α_y² + m_z²)²)          Walter07 eq. 33, anisotropic form of Heitz14
//   Λ(w)    = (−1 + √(1 + (α_x² w_x² + α_y² w_y²)/w_z²)) / 2             Heitz14 (anisotropic GGX)
//   G1(w)   = 1 / (1 + Λ(w))                                            Smith masking (Walter07 eq. 34 when isotropic)
//   D_w(m)  = G1(w)·max(0, w'·m)·D(m) / |w_z|,  w' = w·sign(w_z)         visible normals (Heitz14, Heitz18)
//
// Both materials built on it (rough_conductor.h, rough_dielectric.h) use the separable
// (uncorrelated) masking-shadowing G2(ω_i, ω_o) = G1(ω_i)·G1(ω_o) (Walter07 eq. 23), which is
// symmetric in its two directions and makes every sampled weight f·|cos|/pdf at most 1.
#include "core/math.h"

namespace kasha {

// Accepted roughness: below 0.001 the lobe is narrower than float directions resolve; above 1 GGX
// is no longer a plausible surface.
inline constexpr float kMinAlpha = 1e-3f, kMaxAlpha = 1.0f;

class Ggx {
 public:
  // Roughness α > 0 along x and y (α_x = α_y: isotropic).
  Ggx(float alphaX, float alphaY) : ax_(alphaX), ay_(alphaY) {}

  float alphaX() const { return ax_; }
  float alphaY() const { return ay_; }

  // D(m) per steradian of microfacet normals; 0 for m_z ≤ 0. ∫ D(m)·m_z dm = 1.
  float d(const Vec3& m) const;
  // Smith Λ and G1 for a direction on either side.
  float lambda(const Vec3& w) const;
  float g1(const Vec3& w) const { return 1.0f / (1.0f + lambda(w)); }
  // Density of visible normals D_w(m) (per steradian of m) as seen from w (either side).
  float visiblePdf(const Vec3& w, const Vec3& m) const;
  // Samples m (m_z > 0) from D_w; Heitz18 ("Sampling the GGX distribution of visible normals",
  // JCGT 7(4)): stretch w to the α = 1 configuration, sample the projected hemisphere seen from
  // it as a disk whose far half is squeezed by (1 + w_z)/2, and unstretch the normal.
  Vec3 sampleVisible(const Vec3& w, Vec2 u) const;

  // Microfacet reflection between two directions on the same side, without the Fresnel factor:
  //   D(h)·G1(a)·G1(b) / (4|a_z||b_z|),  h the reflection half vector   (Walter07 eq. 20)
  // symmetric in a and b; 0 for directions on opposite sides.
  float reflection(const Vec3& a, const Vec3& b) const;
  // Density (per sr) of the reflected direction b when a visible normal is sampled from a and a
  // is mirrored about it: D_a(h)·|dh/dω_b| = D_a(h) / (4|a·h|)        (Walter07 eq. 14)
  float reflectionPdf(const Vec3& a, const Vec3& b) const;

 private:
  float ax_, ay_;
};

// A Ggx with α checked against [kMinAlpha, kMaxAlpha]; throws std::invalid_argument
// "alpha: <reason>" otherwise.
Ggx checkedGgx(float alphaX, float alphaY);

// Half vector of reflection between two directions on the same side, m_z ≥ 0 (Walter07 eq. 13).
Vec3 reflectionHalfVector(const Vec3& a, const Vec3& b);
// Generalised half vector of refraction, −(η_a·a + η_b·b) normalised and turned to m_z ≥ 0
// (Walter07 eq. 16); η_a, η_b the indices on the sides of a and b.
Vec3 refractionHalfVector(const Vec3& a, float etaA, const Vec3& b, float etaB);
// Mirror image of w about the microfacet normal m: 2(w·m)m − w (Walter07 eq. 39).
Vec3 reflectAbout(const Vec3& w, const Vec3& m);
// Direction refracted through a facet with normal m (either orientation) from the side of w,
// where eta = η_far/η_w; false under total internal reflection. Snell's law in the facet's frame
// (Walter07 eq. 40): t = −w/η + (c/η − sign(c)·√(1 − (1 − c²)/η²))·m with c = w·m.
bool refractAbout(const Vec3& w, const Vec3& m, float eta, Vec3& t);

}  // namespace kasha
