#include "materials/blend.h"

#include <stdexcept>


namespace kasha {

BsdfFlags BlendModel::blendFlags(BsdfFlags first, BsdfFlags second) {
  const bool fluorescent0 = has(first, BsdfFlags::Fluorescent), fluorescent1 = has(second, BsdfFlags::Fluorescent);
  const bool factorised = fluorescent0 != fluorescent1 && has(fluorescent0 ? first : second, BsdfFlags::FactorisedFluorescence);
  const bool delta0 = has(first, BsdfFlags::DeltaDirection), delta1 = has(second, BsdfFlags::DeltaDirection);
  const bool someDeltas = delta0 != delta1 || has(first, BsdfFlags::DeltaLobe) || has(second, BsdfFlags::DeltaLobe);
  return flagIf(delta0 && delta1, BsdfFlags::DeltaDirection) | flagIf(someDeltas, BsdfFlags::DeltaLobe) |
         flagIf(fluorescent0 || fluorescent1, BsdfFlags::Fluorescent) |
         flagIf(factorised, BsdfFlags::FactorisedFluorescence) |
         flagIf(has(first, BsdfFlags::WavelengthDependentDirection) || has(second, BsdfFlags::WavelengthDependentDirection),
                BsdfFlags::WavelengthDependentDirection);
}

BlendModel::Owners BlendModel::owners(TransportMode mode, const Vec3& wKnown, const Vec3& wSampled, SpectralLobe lobe,
                                      float lambdaIn, float lambdaOut) const {
  Owners delta{{}, true}, weighted{{}, false};
  for (int c = 0; c < 2; ++c) {
    weighted.component[c] = share(c) > 0.0f;
    delta.component[c] = weighted.component[c] && has(components_[c]->flags(), BsdfFlags::DeltaDirection) &&
                         components_[c]->directionPdf({mode, lobe, lambdaIn, lambdaOut}, wKnown, wSampled) > 0.0f;
  }
  return delta.component[0] || delta.component[1] ? delta : weighted;
}

float BlendModel::directionShare(int c, SpectralLobe lobe) const {
  const auto hasLobe = [&](int k) {
    return lobe == SpectralLobe::Elastic || has(components_[k]->flags(), BsdfFlags::Fluorescent);
  };
  const float total = (hasLobe(0) ? share(0) : 0.0f) + (hasLobe(1) ? share(1) : 0.0f);
  return hasLobe(c) && total > 0.0f ? share(c) / total : 0.0f;
}

float BlendModel::eval(const ScatterQuery& query, const Vec3& wi, const Vec3& wo) const {
  const bool radiance = query.mode == TransportMode::Radiance;
  const Owners own =
      owners(query.mode, radiance ? wo : wi, radiance ? wi : wo, query.lobe, query.lambdaIn, query.lambdaOut);
  float f = 0.0f;
  for (int c = 0; c < 2; ++c)
    if (own.component[c]) f += share(c) * components_[c]->eval(query, wi, wo);
  return f;
}

float BlendModel::fluorescenceProbability(TransportMode mode, float lambdaKnown) const {
  return share(0) * components_[0]->fluorescenceProbability(mode, lambdaKnown) +
         share(1) * components_[1]->fluorescenceProbability(mode, lambdaKnown);
}

float BlendModel::spectralPdf(TransportMode mode, float lambdaKnown, float lambdaOther, SpectralLobe lobe) const {
  return share(0) * components_[0]->spectralPdf(mode, lambdaKnown, lambdaOther, lobe) +
         share(1) * components_[1]->spectralPdf(mode, lambdaKnown, lambdaOther, lobe);
}

SpectralChoice BlendModel::sampleSpectral(TransportMode mode, float lambdaKnown, float u) const {
  const float fluorescent0 = share(0) * components_[0]->fluorescenceProbability(mode, lambdaKnown);
  const float fluorescent = fluorescent0 + share(1) * components_[1]->fluorescenceProbability(mode, lambdaKnown);
  if (u < fluorescent) {
    // The component's own fluorescent draw, u rescaled into [0, P_fl,c).
    const int c = u < fluorescent0 ? 0 : 1;
    const float uc = c == 0 ? u / share(0) : (u - fluorescent0) / share(1);
    SpectralChoice choice = components_[c]->sampleSpectral(mode, lambdaKnown, uc);
    if (choice.pdf > 0.0f) choice.pdf = spectralPdf(mode, lambdaKnown, choice.lambda, choice.lobe);
    return choice;
  }
  const float elastic = spectralPdf(mode, lambdaKnown, lambdaKnown, SpectralLobe::Elastic);
  return {SpectralLobe::Elastic, lambdaKnown, u < fluorescent + elastic ? elastic : 0.0f};
}

std::optional<DirectionSample> BlendModel::sampleDirection(const ScatterQuery& query, const Vec3& wKnown,
                                                           Vec2 u) const {
  const float first = directionShare(0, query.lobe), second = directionShare(1, query.lobe);
  if (first + second <= 0.0f) return std::nullopt;
  const int c = u.x < first ? 0 : 1;
  const Vec2 uc(c == 0 ? u.x / first : (u.x - first) / second, u.y);
  std::optional<DirectionSample> ds = components_[c]->sampleDirection(query, wKnown, uc);
  if (!ds) return std::nullopt;
  // The density of the mixture, and whether the direction is a delta's (the sampled one's, or
  // another's within its tolerance: then the delta owns it, as in directionPdf and eval).
  ds->specular = owners(query.mode, wKnown, ds->w, query.lobe, query.lambdaIn, query.lambdaOut).delta;
  ds->pdf = directionPdf(query, wKnown, ds->w);
  return ds;
}

float BlendModel::directionPdf(const ScatterQuery& query, const Vec3& wKnown, const Vec3& wSampled) const {
  const Owners own = owners(query.mode, wKnown, wSampled, query.lobe, query.lambdaIn, query.lambdaOut);
  float pdf = 0.0f;
  for (int c = 0; c < 2; ++c)
    if (own.component[c] && directionShare(c, query.lobe) > 0.0f)
      pdf += directionShare(c, query.lobe) * components_[c]->directionPdf(query, wKnown, wSampled);
  return pdf;
}

BlendMaterial::BlendMaterial(std::unique_ptr<Material> first, std::unique_ptr<Material> second, float weight,
                             ScalarTexture texture)
    : first_(std::move(first)), second_(std::move(second)), weight_(weight), texture_(std::move(texture)) {
  for (const Material* c : {first_.get(), second_.get()}) {
    if (c->textured()) throw std::invalid_argument("a blend of a textured material is not supported");
    if (has(c->flags(), BsdfFlags::DeltaLobe))
      throw std::invalid_argument("a blend of a material with both delta and smooth lobes (" + c->describe() +
                                  ") is not supported");
  }
}

Bsdf BlendMaterial::bsdf(const HitContext& ctx) const {
  // Untextured components' Bsdfs point at the materials themselves, which outlive every hit.
  const Bsdf first = first_->bsdf(ctx), second = second_->bsdf(ctx);
  return Bsdf::inPlace(BlendModel(first.model(), second.model(), texture_.at(weight_, ctx.texturePoint())), ctx);
}

std::optional<FluorophoreSpectra> BlendMaterial::fluorophore() const {
  const std::optional<FluorophoreSpectra> a = first_->fluorophore(), b = second_->fluorophore();
  if (!a || !b) return a ? a : b;
  return FluorophoreSpectra{Spectrum::weightedSum({{1.0f, &a->absorbed}, {1.0f, &b->absorbed}}),
                            Spectrum::weightedSum({{1.0f, &a->reemitted}, {1.0f, &b->reemitted}})};
}

}  // namespace kasha
