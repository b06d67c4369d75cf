#include "materials/opacity_mask.h"

#include <cmath>
#include <stdexcept>

namespace kasha {
namespace {

// The pass-through direction of the known one: exactly −ω (the sampled direction is built so).
bool isPassThrough(const Vec3& a, const Vec3& b) { return a == -b; }

}  // namespace

BsdfFlags MaskModel::maskFlags(BsdfFlags nested) {
  const bool fluorescent = has(nested, BsdfFlags::Fluorescent);
  const bool allDeltas = has(nested, BsdfFlags::DeltaDirection);  // the pass-through is a delta too
  return flagIf(allDeltas, BsdfFlags::DeltaDirection) | flagIf(!allDeltas, BsdfFlags::DeltaLobe) |
         flagIf(fluorescent, BsdfFlags::Fluorescent) |
         flagIf(has(nested, BsdfFlags::FactorisedFluorescence), BsdfFlags::FactorisedFluorescence) |
         BsdfFlags::WavelengthDependentDirection;
}

float MaskModel::elasticProbability(TransportMode mode, float lambda) const {
  return (1.0f - opacity_) + opacity_ * nested_->spectralPdf(mode, lambda, lambda, SpectralLobe::Elastic);
}

float MaskModel::passThroughShare(TransportMode mode, float lambda) const {
  const float elastic = elasticProbability(mode, lambda);
  return elastic > 0.0f ? (1.0f - opacity_) / elastic : 0.0f;
}

float MaskModel::eval(const ScatterQuery& query, const Vec3& wi, const Vec3& wo) const {
  if (query.lobe == SpectralLobe::Elastic && opacity_ < 1.0f && isPassThrough(wi, wo))
    return wi.z != 0.0f ? (1.0f - opacity_) / std::abs(wi.z) : 0.0f;
  return opacity_ * nested_->eval(query, wi, wo);
}

float MaskModel::fluorescenceProbability(TransportMode mode, float lambdaKnown) const {
  return opacity_ * nested_->fluorescenceProbability(mode, lambdaKnown);
}

SpectralChoice MaskModel::sampleSpectral(TransportMode mode, float lambdaKnown, float u) const {
  // The nested material is fluorescent exactly when u/α < P_fl, i.e. u < α·P_fl.
  if (u < fluorescenceProbability(mode, lambdaKnown)) {
    SpectralChoice c = nested_->sampleSpectral(mode, lambdaKnown, u / opacity_);
    c.pdf *= opacity_;
    return c;
  }
  const float elastic = elasticProbability(mode, lambdaKnown);
  return {SpectralLobe::Elastic, lambdaKnown, u < fluorescenceProbability(mode, lambdaKnown) + elastic ? elastic : 0.0f};
}

float MaskModel::spectralPdf(TransportMode mode, float lambdaKnown, float lambdaOther, SpectralLobe lobe) const {
  if (lobe == SpectralLobe::Elastic) return elasticProbability(mode, lambdaKnown);
  return opacity_ * nested_->spectralPdf(mode, lambdaKnown, lambdaOther, lobe);
}

std::optional<DirectionSample> MaskModel::sampleDirection(const ScatterQuery& query, const Vec3& wKnown, Vec2 u) const {
  if (query.lobe == SpectralLobe::Fluorescent) return nested_->sampleDirection(query, wKnown, u);
  const float q = passThroughShare(query.mode, query.lambdaIn);
  if (u.x < q) return DirectionSample{-wKnown, q, true};
  std::optional<DirectionSample> ds = nested_->sampleDirection(query, wKnown, Vec2((u.x - q) / (1.0f - q), u.y));
  if (ds) ds->pdf *= 1.0f - q;
  return ds;
}

float MaskModel::directionPdf(const ScatterQuery& query, const Vec3& wKnown, const Vec3& wSampled) const {
  if (query.lobe == SpectralLobe::Fluorescent) return nested_->directionPdf(query, wKnown, wSampled);
  const float q = passThroughShare(query.mode, query.lambdaIn);
  if (q > 0.0f && isPassThrough(wKnown, wSampled)) return q;
  return (1.0f - q) * nested_->directionPdf(query, wKnown, wSampled);
}

OpacityMask::OpacityMask(std::unique_ptr<Material> nested, float opacity, ScalarTexture texture)
    : nested_(std::move(nested)), opacity_(opacity), texture_(std::move(texture)) {
  if (nested_->textured()) throw std::invalid_argument("a mask around a textured material is not supported");
}

Bsdf OpacityMask::bsdf(const HitContext& ctx) const {
  // An untextured material's Bsdf points at the material itself, which outlives every hit.
  const Bsdf nested = nested_->bsdf(ctx);
  return Bsdf::inPlace(MaskModel(nested.model(), texture_.at(opacity_, ctx.texturePoint())), ctx);
}

}  // namespace kasha
