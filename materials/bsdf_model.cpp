#include "materials/bsdf_model.h"

namespace kasha {

const char* toString(TransportMode m) { return m == TransportMode::Radiance ? "radiance" : "importance"; }

std::optional<ScatterSample> BsdfModel::sample(TransportMode mode, const Vec3& wKnown, float lambdaKnown, Vec3 u) const {
  const SpectralChoice sc = sampleSpectral(mode, lambdaKnown, u.x);
  if (sc.pdf <= 0.0f) return std::nullopt;
  const bool radiance = mode == TransportMode::Radiance;
  const float lambdaIn = radiance ? sc.lambda : lambdaKnown;
  const float lambdaOut = radiance ? lambdaKnown : sc.lambda;
  const std::optional<DirectionSample> ds = sampleDirection(mode, wKnown, sc.lobe, lambdaIn, lambdaOut, Vec2(u.y, u.z));
  if (!ds || ds->pdf <= 0.0f) return std::nullopt;
  const Vec3 wi = radiance ? ds->w : wKnown;
  const Vec3 wo = radiance ? wKnown : ds->w;
  ScatterSample s;
  s.w = ds->w;
  s.lambda = sc.lambda;
  s.lobe = sc.lobe;
  s.specular = ds->specular;
  s.f = eval(mode, wi, wo, lambdaIn, lambdaOut, sc.lobe);
  s.pdf = sc.pdf * ds->pdf;
  s.pdfRev = spectralPdf(flip(mode), sc.lambda, lambdaKnown, sc.lobe) *
             directionPdf(flip(mode), ds->w, wKnown, sc.lobe, lambdaIn, lambdaOut);
  return s;
}

ScatterDensity BsdfModel::pdf(TransportMode mode, const Vec3& wi, const Vec3& wo, float lambdaIn, float lambdaOut,
                             SpectralLobe lobe) const {
  const bool radiance = mode == TransportMode::Radiance;
  const Vec3& wKnown = radiance ? wo : wi;
  const Vec3& wOther = radiance ? wi : wo;
  const float lKnown = radiance ? lambdaOut : lambdaIn;
  const float lOther = radiance ? lambdaIn : lambdaOut;
  ScatterDensity d;
  d.pdf = spectralPdf(mode, lKnown, lOther, lobe) * directionPdf(mode, wKnown, wOther, lobe, lambdaIn, lambdaOut);
  d.pdfRev = spectralPdf(flip(mode), lOther, lKnown, lobe) *
             directionPdf(flip(mode), wOther, wKnown, lobe, lambdaIn, lambdaOut);
  return d;
}

}  // namespace kasha
