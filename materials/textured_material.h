#pragma once
// A material made of a per-hit model (a small, trivially destructible BsdfModel whose heavy data
// the material owns) and the textures of its parameters (materials/surface_texture.h). Untextured,
// every Bsdf points at the material's own model, exactly as a UniformMaterial's; textured, each
// hit gets a copy of that model with the parameters read from the textures there, stored inside
// the Bsdf (Bsdf::inPlace), so no hit allocates.
#include "materials/material.h"
#include "materials/surface_texture.h"

namespace kasha {

template <class Model>
class TexturedMaterial : public Material, public Model {
 public:
  using Model::Model;

  Bsdf bsdf(const HitContext& ctx) const final {
    if (!textured()) return Bsdf(static_cast<const Model&>(*this), ctx);
    return Bsdf::inPlace(modelAt(ctx.texturePoint()), ctx);
  }
  // The material's own model's flags: textures only scale parameters down, so they are the union
  // over the surface.
  BsdfFlags flags() const final { return Model::flags(); }

 protected:
  // The model at point p (called only when textured()).
  virtual Model modelAt(const TexturePoint& p) const = 0;
};

// A non-fluorescent material whose one parameter is a reflectance spectrum, optionally textured
// ("reflectance_texture"): its Model is built from a HitReflectance.
template <class Model>
class ReflectanceMaterial : public TexturedMaterial<Model> {
 public:
  explicit ReflectanceMaterial(Spectrum reflectance, ReflectanceTexture texture = {})
      : TexturedMaterial<Model>(HitReflectance{&spectrum_}),
        spectrum_(std::move(reflectance)),
        texture_(std::move(texture)) {}
  std::optional<FluorophoreSpectra> fluorophore() const final { return std::nullopt; }
  bool textured() const final { return texture_.texture != nullptr; }
  std::vector<const Texture*> textures() const final { return setTextures(texture_); }
  const Spectrum& reflectance() const { return spectrum_; }

 private:
  Model modelAt(const TexturePoint& p) const final { return Model(texture_.at(spectrum_, p)); }
  Spectrum spectrum_;
  ReflectanceTexture texture_;
};

}  // namespace kasha
