#pragma once
// An opacity mask (Mitsuba 3: mask): with probability 1 − α the surface is not there and light
// passes straight on, unchanged; with probability α the nested material scatters it. α (opacity)
// may be textured (leaves cut out of a sheet). The pass-through is a lobe of the BSDF, a Dirac
// delta at ω_o = −ω_i with the coefficient (1 − α)/|cos θ| (the same in both transport modes: the
// light stays in the medium it came from, as thin_dielectric.h's transmission), so every
// integrator gets it through the Bsdf interface: sampled, it continues the path as a specular
// direction; next-event estimation, connections and photon gathering see α times the nested f.
//
// Spectral stage: the fluorescent lobe has probability α·P_fl (the nested material's choice, drawn
// with u/α), the elastic one (1 − α) + α·P_el, P_el the nested elastic lobe's. Directional stage of
// the elastic lobe: the pass-through with probability q = (1 − α)/((1 − α) + α·P_el), else the
// nested material's direction (u rescaled), with density (1 − q)·p_nested. With α = 1 every draw
// and value is the nested material's (bit for bit); with α = 0 the surface only passes light on.
//
// The nested material must be untextured (its per-hit model is then the material itself, which
// the mask's per-hit model points to); a textured one is refused.
#include <memory>

#include "materials/material.h"
#include "materials/surface_texture.h"

namespace kasha {

// The model at one hit.
class MaskModel final : public BsdfModel {
 public:
  MaskModel(const BsdfModel& nested, float opacity) : nested_(&nested), opacity_(opacity) {}

  float eval(const ScatterQuery& query, const Vec3& wi, const Vec3& wo) const override;
  SpectralChoice sampleSpectral(TransportMode mode, float lambdaKnown, float u) const override;
  float spectralPdf(TransportMode mode, float lambdaKnown, float lambdaOther, SpectralLobe lobe) const override;
  float fluorescenceProbability(TransportMode mode, float lambdaKnown) const override;
  std::optional<DirectionSample> sampleDirection(const ScatterQuery& query, const Vec3& wKnown, Vec2 u) const override;
  float directionPdf(const ScatterQuery& query, const Vec3& wKnown, const Vec3& wSampled) const override;
  // Opaque (α = 1), the nested model's; else maskFlags.
  BsdfFlags flags() const override { return opacity_ < 1.0f ? maskFlags(nested_->flags()) : nested_->flags(); }

  // A mask's flags around a nested model's: the pass-through is a delta, so the mask is all deltas
  // only where the nested model is; the pass-through's probability q depends on the wavelength
  // wherever the nested lobes' probabilities may (a fluorescent material, a zero reflectance), so
  // its direction density does.
  static BsdfFlags maskFlags(BsdfFlags nested);

 private:
  // The elastic lobe's probability, and the pass-through's share q of it.
  float elasticProbability(TransportMode mode, float lambda) const;
  float passThroughShare(TransportMode mode, float lambda) const;

  const BsdfModel* nested_;
  float opacity_;
};

class OpacityMask final : public Material {
 public:
  // opacity α ∈ [0, 1], times the texture where given. Throws std::invalid_argument if `nested`
  // is textured.
  OpacityMask(std::unique_ptr<Material> nested, float opacity, ScalarTexture texture);
  Bsdf bsdf(const HitContext& ctx) const override;
  BsdfFlags flags() const override { return MaskModel::maskFlags(nested_->flags()); }
  std::optional<FluorophoreSpectra> fluorophore() const override { return nested_->fluorophore(); }
  bool textured() const override { return texture_.texture != nullptr; }
  std::vector<const Texture*> textures() const override { return setTextures(texture_); }
  std::string describe() const override { return "mask(" + nested_->describe() + ")"; }

 private:
  std::unique_ptr<Material> nested_;
  float opacity_;
  ScalarTexture texture_;
};

}  // namespace kasha
