#pragma once
// Fresnel reflectance of a smooth interface between two lossless dielectrics, for unpolarised
// light: the mean of the s and p power reflectances (Born & Wolf, Principles of Optics, §1.5.3;
// Hecht, Optics, eqs. 4.42–4.43):
//   r_s = (cos θ_i − η·cos θ_t) / (cos θ_i + η·cos θ_t)
//   r_p = (η·cos θ_i − cos θ_t) / (η·cos θ_i + cos θ_t)
//   F   = (r_s² + r_p²) / 2,   with η = η_t/η_i and sin θ_t = sin θ_i/η (Snell),
// and F = 1 under total internal reflection. F is the same from both sides of one event:
// F(θ_i, η) = F(θ_t, 1/η) (r_s and r_p only change sign), so the reflect/refract probabilities of
// a path and of its reverse agree.
//
// Fresnel reflectance of a conductor with complex relative index η + i·k, unpolarised, from the
// outside at angle θ (Born & Wolf §14.2; in the form of PBR3 §8.2.1 "Fresnel reflectance"):
//   a² + b² = sqrt((η² − k² − sin²θ)² + 4η²k²),   a = sqrt((a² + b² + η² − k² − sin²θ)/2)
//   R_s = (a² + b² − 2a·cos θ + cos²θ) / (a² + b² + 2a·cos θ + cos²θ)
//   R_p = R_s·(cos²θ(a² + b²) − 2a·cos θ·sin²θ + sin⁴θ) / (cos²θ(a² + b²) + 2a·cos θ·sin²θ + sin⁴θ)
//   F   = (R_s + R_p) / 2,
// which at normal incidence is ((η − 1)² + k²)/((η + 1)² + k²) and for k = 0 the dielectric's.
#include <algorithm>
#include <cmath>

namespace kasha {

// cosThetaI in [0, 1] on the incident side; eta = η_t/η_i.
inline float fresnelDielectric(float cosThetaI, float eta) {
  const float cosI = std::clamp(cosThetaI, 0.0f, 1.0f);
  const float sin2T = (1.0f - cosI * cosI) / (eta * eta);
  if (sin2T >= 1.0f) return 1.0f;
  const float cosT = std::sqrt(1.0f - sin2T);
  const float rs = (cosI - eta * cosT) / (cosI + eta * cosT);
  const float rp = (eta * cosI - cosT) / (eta * cosI + cosT);
  return 0.5f * (rs * rs + rp * rp);
}

// cosThetaI in [0, 1]; eta and k of the conductor relative to the outside.
inline float fresnelConductor(float cosThetaI, float eta, float k) {
  const float c = std::clamp(cosThetaI, 0.0f, 1.0f);
  const float c2 = c * c, s2 = 1.0f - c2;
  const float t0 = eta * eta - k * k - s2;
  const float a2b2 = std::sqrt(t0 * t0 + 4.0f * eta * eta * k * k);
  const float a = std::sqrt(std::max(0.5f * (a2b2 + t0), 0.0f));
  const float rs = (a2b2 - 2.0f * a * c + c2) / (a2b2 + 2.0f * a * c + c2);
  const float t1 = c2 * a2b2 + s2 * s2, t2 = 2.0f * a * c * s2;
  const float rp = rs * (t1 - t2) / (t1 + t2);
  return 0.5f * (rs + rp);
}

}  // namespace kasha
