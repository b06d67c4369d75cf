#include "materials/volume_scattering.h"

#include <cmath>

#include "core/sampling.h"

namespace kasha {

float henyeyGreenstein(float cosTheta, float g) {
  const float denom = 1.0f + g * g - 2.0f * g * cosTheta;
  return (1.0f - g * g) / (4.0f * kPi * denom * std::sqrt(std::max(denom, 1e-12f)));
}

Vec3 sampleHenyeyGreenstein(const Vec3& axis, float g, Vec2 u) {
  float cosTheta;
  if (std::abs(g) < 1e-3f) {
    cosTheta = 1.0f - 2.0f * u.x;
  } else {
    // The inverse of the CDF in cos θ (Henyey & Greenstein 1941; PBR4 eq. 11.12).
    const float s = (1.0f - g * g) / (1.0f - g + 2.0f * g * u.x);
    cosTheta = (1.0f + g * g - s * s) / (2.0f * g);
  }
  cosTheta = std::clamp(cosTheta, -1.0f, 1.0f);
  const float sinTheta = std::sqrt(std::max(0.0f, 1.0f - cosTheta * cosTheta));
  const float phi = 2.0f * kPi * u.y;
  return Frame::fromNormal(axis).toWorld(Vec3(sinTheta * std::cos(phi), sinTheta * std::sin(phi), cosTheta));
}

VolumeScattering::VolumeScattering(const Medium& medium, std::optional<RgbSigmoid> albedoHere)
    : medium_(&medium), albedoHere_(albedoHere) {
  const size_t n = fluorophoreCount();
  flags_ = BsdfFlags::Volume | flagIf(medium.fluoresces(), BsdfFlags::Fluorescent) |
           flagIf(medium.fluoresces() && n == 1, BsdfFlags::FactorisedFluorescence);
}

float VolumeScattering::fluorescentShare(TransportMode mode, size_t k, float lambdaKnown) const {
  const Fluorophore& f = medium_->params().fluorophores[k];
  // media.md eq. 5: Radiance Y_k·ê_k(λ_o)·∫σ_f,k; Importance σ_f,k(λ_i)·Y_k (∫ê_k = 1).
  return mode == TransportMode::Radiance
             ? f.yield * medium_->emissionDistribution(k).pdf(lambdaKnown) * medium_->absorptionIntegral(k)
             : f.yield * f.absorption(lambdaKnown);
}

float VolumeScattering::scattering(float lambda) const {
  return albedoHere_ ? (*albedoHere_)(lambda) * medium_->sigmaT(lambda) : medium_->sigmaS(lambda);
}

float VolumeScattering::fluorescentWeight(TransportMode mode, float lambdaKnown) const {
  float a = 0.0f;
  for (size_t k = 0; k < fluorophoreCount(); ++k) a += fluorescentShare(mode, k, lambdaKnown);
  return a;
}

float VolumeScattering::albedoWeight(TransportMode mode, float lambdaKnown) const {
  return scattering(lambdaKnown) + fluorescentWeight(mode, lambdaKnown);
}

float VolumeScattering::eval(const ScatterQuery& query, const Vec3& wi, const Vec3& wo) const {
  if (query.lobe == SpectralLobe::Elastic)  // media.md eq. 3
    return scattering(query.lambdaIn) * henyeyGreenstein(-glm::dot(wi, wo), medium_->params().g);
  float f = 0.0f;  // media.md eq. 4
  for (size_t k = 0; k < fluorophoreCount(); ++k) {
    const Fluorophore& fl = medium_->params().fluorophores[k];
    f += fl.absorption(query.lambdaIn) * fl.yield * medium_->emissionDistribution(k).pdf(query.lambdaOut);
  }
  return f * kUniformSpherePdf;
}

float VolumeScattering::fluorescenceProbability(TransportMode mode, float lambdaKnown) const {
  const float fl = fluorescentWeight(mode, lambdaKnown), total = fl + scattering(lambdaKnown);
  return total > 0.0f ? fl / total : 0.0f;
}

SpectralChoice VolumeScattering::sampleSpectral(TransportMode mode, float lambdaKnown, float u) const {
  SpectralChoice c;
  const float fl = fluorescentWeight(mode, lambdaKnown), total = fl + scattering(lambdaKnown);
  if (!(total > 0.0f)) return c;
  const float pFl = fl / total;
  if (!(u < pFl)) {
    c.lambda = lambdaKnown;
    c.pdf = 1.0f - pFl;
    return c;
  }
  // The fluorophore in proportion to its share, then the unknown wavelength from it, with the
  // remainder of u.
  float v = u / pFl * fl;
  size_t k = 0;
  const size_t n = fluorophoreCount();
  for (; k + 1 < n; ++k) {
    const float share = fluorescentShare(mode, k, lambdaKnown);
    if (v < share) break;
    v -= share;
  }
  const float share = fluorescentShare(mode, k, lambdaKnown);
  const float w = share > 0.0f ? std::clamp(v / share, 0.0f, 0x1.fffffep-1f) : 0.0f;
  const WavelengthSample s = mode == TransportMode::Radiance ? medium_->absorptionDistribution(k).sample(w)
                                                             : medium_->emissionDistribution(k).sample(w);
  c.lobe = SpectralLobe::Fluorescent;
  c.lambda = s.lambda;
  c.pdf = spectralPdf(mode, lambdaKnown, s.lambda, SpectralLobe::Fluorescent);
  return c;
}

float VolumeScattering::spectralPdf(TransportMode mode, float lambdaKnown, float lambdaOther, SpectralLobe lobe) const {
  const float fl = fluorescentWeight(mode, lambdaKnown), total = fl + scattering(lambdaKnown);
  if (!(total > 0.0f)) return 0.0f;
  if (lobe == SpectralLobe::Elastic) return scattering(lambdaKnown) / total;
  // Σ_k share_k/total · (σ_f,k or ê_k density at the other wavelength) = 4π·f_fl/total.
  const bool radiance = mode == TransportMode::Radiance;
  const float f = eval(
      {mode, SpectralLobe::Fluorescent, radiance ? lambdaOther : lambdaKnown, radiance ? lambdaKnown : lambdaOther},
      Vec3(0.0f), Vec3(0.0f));
  return f / kUniformSpherePdf / total;
}

std::optional<DirectionSample> VolumeScattering::sampleDirection(const ScatterQuery& query, const Vec3& wKnown,
                                                                 Vec2 u) const {
  DirectionSample ds;
  if (query.lobe == SpectralLobe::Fluorescent) {
    ds.w = sampleUniformSphere(u);
    ds.pdf = kUniformSpherePdf;
    return ds;
  }
  // Radiance: ω_i with −ω_i about ω_o; Importance: ω_o about −ω_i (cos θ = −ω_i·ω_o both ways).
  const float g = medium_->params().g;
  const Vec3 travel = sampleHenyeyGreenstein(query.mode == TransportMode::Radiance ? wKnown : -wKnown, g, u);
  ds.w = query.mode == TransportMode::Radiance ? -travel : travel;
  ds.pdf = henyeyGreenstein(glm::dot(travel, query.mode == TransportMode::Radiance ? wKnown : -wKnown), g);
  return ds;
}

float VolumeScattering::directionPdf(const ScatterQuery& query, const Vec3& wKnown, const Vec3& wSampled) const {
  if (query.lobe == SpectralLobe::Fluorescent) return kUniformSpherePdf;
  const Vec3& wi = query.mode == TransportMode::Radiance ? wSampled : wKnown;
  const Vec3& wo = query.mode == TransportMode::Radiance ? wKnown : wSampled;
  return henyeyGreenstein(-glm::dot(wi, wo), medium_->params().g);
}

}  // namespace kasha
