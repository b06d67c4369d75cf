#pragma once
// Jung18's BBRRDF (jung_bbrrdf.h) with parameters that vary over the surface: the reflectance
// r(λ), the concentration c and the energy ratio Q each multiplied by a scalar image texture
// (core/texture.h) in [0, 1], so that fluorescent ink printed on paper is a c texture.
//
// At a hit, the material's Bsdf is that of an ordinary JungBbrrdf: every distinct combination of
// texel values becomes one JungBbrrdf, built at load time (a palette: 8-bit images of ink give a
// handful), and each texel points to its entry, which lives as long as the scene. The price is
// nearest-texel lookup: values between texels would be materials not in the palette.
#include <memory>
#include <optional>
#include <vector>

#include "core/texture.h"
#include "materials/jung_bbrrdf.h"

namespace kasha {

struct JungTextures {
  std::shared_ptr<const ImageTexture> reflectance, c, q;  // multipliers of r(λ), c and Q; absent: 1
};

class TexturedJung final : public Material {
 public:
  // Largest palette: more distinct texel combinations are an error (quantise the images).
  static constexpr size_t kMaxPalette = 4096;

  // Throws std::invalid_argument "field: reason" ("reflectance_texture", "c_texture",
  // "Q_texture") for textures of different sizes or too many distinct values, or the message of
  // checkJungParams for invalid base parameters.
  TexturedJung(JungParams base, JungTextures textures, WavelengthRange range);

  // The palette entry of the texel at ctx.uv.
  Bsdf bsdf(const HitContext& ctx) const override { return Bsdf(*palette_[index_[grid_->texelIndex(ctx.uv)]], ctx); }
  bool textured() const override { return true; }
  size_t paletteSize() const { return palette_.size(); }
  BsdfFlags flags() const override { return flags_; }
  // The texel-area mean of the entries' spectra (the same shapes, scaled by c and c·Q).
  std::optional<FluorophoreSpectra> fluorophore() const override { return fluorophore_; }
  std::string describe() const override { return "jung_fluorescent (textured)"; }

 private:
  std::shared_ptr<const ImageTexture> grid_;  // the texel grid shared by every texture (values unused)
  std::vector<std::unique_ptr<JungBbrrdf>> palette_;
  std::vector<uint32_t> index_;  // palette entry per texel
  BsdfFlags flags_ = BsdfFlags::None;               // the union of the entries'
  std::optional<FluorophoreSpectra> fluorophore_;  // none if no entry fluoresces
};

}  // namespace kasha
