#pragma once
// A material is the scene object (parameters, textures, JSON): at each hit it builds the
// scattering function there, a Bsdf (materials/bsdf.h), from the hit's context. Integrators see
// only Bsdfs (Scene::bsdf); wavelength strategies read what each material absorbs and re-emits.
#include <optional>
#include <string>
#include <vector>

#include "core/spectrum.h"
#include "materials/bsdf.h"

namespace kasha {

// What a fluorescent material absorbs and re-emits, for the wavelength strategies that follow the
// scene's fluorophores (docs/wavelength-sampling.md). A strategy's density must be positive
// wherever `absorbed` is (excitation) or `reemitted` is (emission), so both must cover the
// material's support, at least where it varies over the surface.
struct FluorophoreSpectra {
  Spectrum absorbed;   // fraction of the energy arriving at λ_i that the fluorophore absorbs
  Spectrum reemitted;  // energy re-emitted per nm at λ_o under unit white irradiance (1 per nm)
};

class Material {
 public:
  virtual ~Material() = default;

  // The scattering function at one hit (its directions local to ctx.shading). No heap allocation.
  virtual Bsdf bsdf(const HitContext& ctx) const = 0;
  // The union of the flags of every Bsdf it builds (BsdfFlags).
  virtual BsdfFlags flags() const = 0;
  // What it absorbs and re-emits: set for every material whose flags() are Fluorescent.
  virtual std::optional<FluorophoreSpectra> fluorophore() const = 0;
  virtual std::string describe() const = 0;
  // True if its Bsdf depends on where it is hit (a texture; the hot path asks this, so it is not
  // computed from textures()).
  virtual bool textured() const { return false; }
  // Its parameters' textures, for the checks of the shapes it is on (texture coordinates, mesh
  // attributes); empty exactly when textured() is false.
  virtual std::vector<const Texture*> textures() const { return {}; }

  // Scatters only light that arrives at and leaves its front (Mitsuba's one-sided BSDFs, black from
  // behind; JSON "one_sided"): Scene::bsdf restricts its Bsdf (Bsdf::restrictToFront).
  bool oneSided = false;
};

// A material that scatters the same everywhere: it is its own per-hit model, a Model (BsdfModel or
// one with shared stages, such as ElasticModel).
template <class Model>
class UniformMaterial : public Material, public Model {
 public:
  Bsdf bsdf(const HitContext& ctx) const final { return Bsdf(*this, ctx); }
};

}  // namespace kasha
