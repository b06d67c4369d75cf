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

}  // namespace kasha
