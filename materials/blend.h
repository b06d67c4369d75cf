#pragma once
// A blend of two materials (Mitsuba 3: blendbsdf): with weight w ∈ [0, 1], a float that a texture
// may multiply, every lobe of the blend is the weighted sum of the components' lobes,
//
//   f(ω_i, λ_i → ω_o, λ_o) = (1 − w)·f_0 + w·f_1        (Mitsuba 3 docs: blendbsdf)
//
// per spectral lobe, in either transport mode, so a fluorescent component's lobe is forwarded
// with its weight. With a_0 = 1 − w and a_1 = w:
//
// Spectral stage: the mixture of the components' own. P_fl = a_0·P_fl,0 + a_1·P_fl,1, drawn as
// bsdf_model.h requires (fluorescent exactly when u < P_fl): u < a_0·P_fl,0 gives component 0's
// fluorescent draw with u/a_0, u < P_fl component 1's with (u − a_0·P_fl,0)/a_1; above, the
// elastic lobe with probability a_0·P_el,0 + a_1·P_el,1. The density of (lobe, λ) is
// a_0·p_0(lobe, λ) + a_1·p_1(lobe, λ) whichever component drew it.
//
// Directional stage, given the lobe: a component is picked with probability π_c ∝ a_c over the
// components that have the lobe (both for the elastic one, so π_c = a_c; the fluorescent ones for
// the fluorescent lobe), independently of the wavelengths, and the density is the mixture
// π_0·p_0(ω) + π_1·p_1(ω). For two elastic components the event's density is thus
// P_el·((1 − w)·p_0 + w·p_1), Mitsuba's mixture density times the probability of scattering.
//
// Delta lobes (specular_lobe.h): where a component that is all deltas (BsdfFlags::DeltaDirection)
// has a nonzero direction density, the direction is its delta's (within specular::matches), and
// the value and density there are those delta components' alone, a_c·f_c and Σ π_c·P_c; a
// smooth lobe's finite value has no weight against a Dirac delta. So a sampled delta carries its
// own path weight a_c·f_c·|cos|/(π_c·P_c), and is reported specular; the blend is all deltas only
// if both components are.
//
// The components must be untextured (their per-hit models are the materials themselves, which
// the blend's per-hit model points to; the weight may be textured), and neither may mix delta and
// smooth lobes itself (a mask around a smooth material, a blend of a delta and a smooth one),
// whose deltas the blend could not tell apart from its smooth lobes; both are refused.
#include <array>
#include <memory>

#include "materials/material.h"
#include "materials/surface_texture.h"

namespace kasha {

// The model at one hit.
class BlendModel final : public BsdfModel {
 public:
  // Both components must outlive the model (the materials'). weight ∈ [0, 1].
  BlendModel(const BsdfModel& first, const BsdfModel& second, float weight)
      : components_{&first, &second}, weight_(weight) {}

  // Σ a_c·f_c over the components that own the event (owners()).
  float eval(const ScatterQuery& query, const Vec3& wi, const Vec3& wo) const override;
  // Σ a_c·P_fl,c and Σ a_c·p_c(lobe, λ): the mixture's spectral stage.
  float fluorescenceProbability(TransportMode mode, float lambdaKnown) const override;
  float spectralPdf(TransportMode mode, float lambdaKnown, float lambdaOther, SpectralLobe lobe) const override;
  // A component's own draw where u says fluorescent, with the mixture's density.
  SpectralChoice sampleSpectral(TransportMode mode, float lambdaKnown, float u) const override;
  // One component's direction (chosen with π_c), reported with the mixture's density and as
  // specular where a delta owns it.
  std::optional<DirectionSample> sampleDirection(const ScatterQuery& query, const Vec3& wKnown, Vec2 u) const override;
  // Σ π_c·p_c over the components that own the event.
  float directionPdf(const ScatterQuery& query, const Vec3& wKnown, const Vec3& wSampled) const override;
  BsdfFlags flags() const override { return blendFlags(components_[0]->flags(), components_[1]->flags()); }

  // A blend's flags from its components': all deltas if both are, fluorescent if either is,
  // FactorisedFluorescence if exactly one fluoresces and it has it (two fluorescent components'
  // mixture of excitation densities depends on the known wavelength), and a direction density
  // that depends on λ if either component's does (the component choice does not).
  static BsdfFlags blendFlags(BsdfFlags first, BsdfFlags second);

 private:
  // The components that own the event (wKnown → wSampled) of `lobe`: the delta components whose
  // delta it is, if any (then `delta`), else every component of nonzero weight.
  struct Owners {
    std::array<bool, 2> component{};
    bool delta = false;
  };
  Owners owners(TransportMode mode, const Vec3& wKnown, const Vec3& wSampled, SpectralLobe lobe,
                             float lambdaIn, float lambdaOut) const;
  // a_c: 1 − w for the first component, w for the second.
  float share(int c) const { return c == 0 ? 1.0f - weight_ : weight_; }
  // π_c: the probability that the directional stage of `lobe` samples component c.
  float directionShare(int c, SpectralLobe lobe) const;

  std::array<const BsdfModel*, 2> components_;
  float weight_;
};

class BlendMaterial final : public Material {
 public:
  // weight ∈ [0, 1], times the texture where given. Throws std::invalid_argument "reason" for a
  // textured component or one that mixes delta and smooth lobes.
  BlendMaterial(std::unique_ptr<Material> first, std::unique_ptr<Material> second, float weight, ScalarTexture texture);
  Bsdf bsdf(const HitContext& ctx) const override;
  BsdfFlags flags() const override { return BlendModel::blendFlags(first_->flags(), second_->flags()); }
  // The fluorescent components' spectra; of two, their sums (covering both supports).
  std::optional<FluorophoreSpectra> fluorophore() const override;
  bool textured() const override { return texture_.texture != nullptr; }
  std::vector<const Texture*> textures() const override { return setTextures(texture_); }
  std::string describe() const override { return "blend(" + first_->describe() + ", " + second_->describe() + ")"; }

 private:
  std::unique_ptr<Material> first_, second_;
  float weight_;
  ScalarTexture texture_;
};

}  // namespace kasha
