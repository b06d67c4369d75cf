#pragma once
// Normal and bump maps (Mitsuba 3: normalmap, bumpmap): a material that scatters as a nested
// material does, in a shading frame whose normal an image tilts at each hit. The tilted frame
// goes to the nested material through HitContext::shading, the same path as a mesh's vertex
// normals, so every integrator gets it with Veach's shading-normal correction (shading_normal.h).
//
// Tangent frame at a hit: n the shading normal, s the part of ∂p/∂u orthogonal to n (HitContext::
// dpdu), t = n × s; a map's normal (x, y, z) means x·s + y·t + z·n. The tilted normal n' gets the
// frame (s', t', n') with s' the part of ∂p/∂u orthogonal to n' (Mitsuba 3 does the same).
//  - Normal map: (x, y, z) = 2·rgb − 1 of a three-channel image (a tangent-space normal map).
//  - Bump map: the surface displaced along n by scale·h(u, v) has the tangents ∂p/∂u + n·scale·∂h/∂u
//    and ∂p/∂v + n·scale·∂h/∂v (their components along n replaced, as in Mitsuba 3: Blinn 1978's
//    approximation without the normal's own derivative); n' is their cross product, turned to the
//    geometric normal's side. ∂h/∂u, ∂h/∂v: the texture's gradient (Texture::scalarGradient: a
//    bilinear image's; nearest filtering and checkerboards have none).
// A map that leaves the normal as it is ((0, 0, 1) in the tangent frame, e.g. rgb (½, ½, 1) or a
// constant height) gives the nested material's Bsdf unchanged, bit for bit. A tilted normal that
// is not strictly on the geometric normal's side (or not finite) keeps the unperturbed frame:
// Mitsuba instead flips such a normal towards the incident direction, which a Bsdf built before
// the direction is known cannot do.
#include <memory>
#include <vector>

#include "core/texture.h"
#include "materials/material.h"

namespace kasha {

// The wrapper: the nested material's flags, fluorophore and Bsdf, in the tilted shading frame.
class PerturbedNormalMaterial : public Material {
 public:
  PerturbedNormalMaterial(std::unique_ptr<Material> nested, std::shared_ptr<const Texture> map)
      : nested_(std::move(nested)), map_(std::move(map)) {}
  Bsdf bsdf(const HitContext& ctx) const final;
  BsdfFlags flags() const final { return nested_->flags(); }
  std::optional<FluorophoreSpectra> fluorophore() const final { return nested_->fluorophore(); }
  bool textured() const final { return true; }
  // The nested material's textures and the map.
  std::vector<const Texture*> textures() const final;
  const Material& nested() const { return *nested_; }

 protected:
  // The tilted normal at the hit in the tangent frame (any length; (0, 0, 1): unperturbed).
  virtual Vec3 tangentNormal(const HitContext& ctx, const Frame& tangent) const = 0;
  const Texture& map() const { return *map_; }

 private:
  std::unique_ptr<Material> nested_;
  std::shared_ptr<const Texture> map_;
};

class NormalMapMaterial final : public PerturbedNormalMaterial {
 public:
  // `normals`: three channels, values in [0, 1].
  NormalMapMaterial(std::unique_ptr<Material> nested, std::shared_ptr<const Texture> normals);
  std::string describe() const override { return "normal_map(" + nested().describe() + ")"; }

 private:
  Vec3 tangentNormal(const HitContext& ctx, const Frame& tangent) const override;
};

class BumpMapMaterial final : public PerturbedNormalMaterial {
 public:
  // `height`: one channel, values in [0, 1], scaled by `scale` (a length in scene units per unit value).
  BumpMapMaterial(std::unique_ptr<Material> nested, std::shared_ptr<const Texture> height, float scale);
  std::string describe() const override { return "bump_map(" + nested().describe() + ")"; }

 private:
  Vec3 tangentNormal(const HitContext& ctx, const Frame& tangent) const override;
  float scale_;
};

}  // namespace kasha
