#pragma once
// Jung18's BBRRDF (jung_bbrrdf.h) with parameters that vary over the surface: the reflectance
// r(λ), the concentration c and the energy ratio Q each multiplied by a scalar image texture
// (core/texture.h) in [0, 1], so that fluorescent ink printed on paper is a c texture.
//
// The material interface takes no position, so a textured material is resolved before any
// integrator sees it: Scene::material(hit) calls at(uv) at the hit, which returns an ordinary
// JungBbrrdf. Every distinct combination of texel values becomes one JungBbrrdf, built at load
// time (a palette: 8-bit images of ink give a handful), and each texel points to its entry. So
// every integrator keeps its one code path, and a resolved material lives as long as the scene.
// The price is nearest-texel lookup: values between texels would be materials not in the
// palette. The unresolved material's own sampling and evaluation must not be called.
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

  const Material& at(Vec2 uv) const override { return *palette_[index_[grid_->texelIndex(uv)]]; }
  bool textured() const override { return true; }
  size_t paletteSize() const { return palette_.size(); }

  // Unresolved use is a programming error: these throw std::logic_error.
  float eval(TransportMode mode, const Vec3& wi, const Vec3& wo, float lambdaIn, float lambdaOut,
             SpectralLobe lobe) const override;
  SpectralChoice sampleSpectral(TransportMode mode, float lambdaKnown, float u) const override;
  float spectralPdf(TransportMode mode, float lambdaKnown, float lambdaOther, SpectralLobe lobe) const override;
  std::optional<DirectionSample> sampleDirection(TransportMode mode, const Vec3& wKnown, SpectralLobe lobe,
                                                 float lambdaIn, float lambdaOut, Vec2 u) const override;
  float directionPdf(TransportMode mode, const Vec3& wKnown, const Vec3& wSampled, SpectralLobe lobe, float lambdaIn,
                     float lambdaOut) const override;
  bool fluoresces() const override;
  std::string describe() const override { return "jung_fluorescent (textured)"; }

 private:
  std::shared_ptr<const ImageTexture> grid_;  // the texel grid shared by every texture (values unused)
  std::vector<std::unique_ptr<JungBbrrdf>> palette_;
  std::vector<uint32_t> index_;  // palette entry per texel
};

}  // namespace kasha
