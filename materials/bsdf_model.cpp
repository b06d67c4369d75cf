#include "materials/bsdf_model.h"

namespace kasha {

const char* toString(TransportMode m) { return m == TransportMode::Radiance ? "radiance" : "importance"; }

std::optional<ScatterSample> BsdfModel::sample(TransportMode mode, const Vec3& wKnown, float lambdaKnown, Vec3 u) const {
  const SpectralChoice sc = sampleSpectral(mode, lambdaKnown, u.x);
  if (sc.pdf <= 0.0f) return std::nullopt;
  const bool radiance = mode == TransportMode::Radiance;
  const float lambdaIn = radiance ? sc.lambda : lambdaKnown;
  const float lambdaOut = radiance ? lambdaKnown : sc.lambda;
  const std::optional<DirectionSample> ds =
      sampleDirection({mode, sc.lobe, lambdaIn, lambdaOut}, wKnown, Vec2(u.y, u.z));
  if (!ds || ds->pdf <= 0.0f) return std::nullopt;
  const Vec3 wi = radiance ? ds->w : wKnown;
  const Vec3 wo = radiance ? wKnown : ds->w;
  ScatterSample s;
  s.w = ds->w;
  s.lambda = sc.lambda;
  s.lobe = sc.lobe;
  s.specular = ds->specular;
  s.f = eval({mode, sc.lobe, lambdaIn, lambdaOut}, wi, wo);
  s.pdf = sc.pdf * ds->pdf;
  s.pdfRev = spectralPdf(flip(mode), sc.lambda, lambdaKnown, sc.lobe) *
             directionPdf({flip(mode), sc.lobe, lambdaIn, lambdaOut}, ds->w, wKnown);
  return s;
}

ScatterDensity BsdfModel::pdf(const ScatterQuery& query, const Vec3& wi, const Vec3& wo) const {
  const bool radiance = query.mode == TransportMode::Radiance;
  const Vec3& wKnown = radiance ? wo : wi;
  const Vec3& wOther = radiance ? wi : wo;
  const float lKnown = radiance ? query.lambdaOut : query.lambdaIn;
  const float lOther = radiance ? query.lambdaIn : query.lambdaOut;
  ScatterDensity d;
  d.pdf = spectralPdf(query.mode, lKnown, lOther, query.lobe) * directionPdf(query, wKnown, wOther);
  d.pdfRev = spectralPdf(flip(query.mode), lOther, lKnown, query.lobe) *
             directionPdf({flip(query.mode), query.lobe, query.lambdaIn, query.lambdaOut}, wOther, wKnown);
  return d;
}

}  // namespace kasha
