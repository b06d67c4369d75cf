#pragma once
// Material parameters that vary over a surface: a texture (core/texture.h: an image, a
// checkerboard, a mesh attribute) read at the hit, multiplying the material's value there. A
// reflectance texture has one channel (a factor on the spectrum) or three (a linear sRGB colour whose Jakob–Hanika
// spectrum, core/rgb_spectrum.h, multiplies the spectrum: with the spectrum 1, the colour).
// Without a texture the value is the material's own, unchanged bit for bit (×1).
#include <algorithm>
#include <memory>
#include <vector>

#include "core/rgb_spectrum.h"
#include "core/spectrum.h"
#include "core/texture.h"
#include "materials/ggx.h"

namespace kasha {

// A reflectance spectrum at one hit: scale·s(λ)·(sigmoid(λ) if a colour was given).
struct HitReflectance {
  const Spectrum* spectrum = nullptr;  // the material's, which outlives every hit
  float scale = 1.0f;
  bool colour = false;
  RgbSigmoid sigmoid{};
  float operator()(float lambda) const {
    const float v = scale * (*spectrum)(lambda);
    return colour ? v * sigmoid(lambda) : v;
  }
  // r(λ) > 0, without a lookup where the scaled spectrum's least value is already > 0 (rounding
  // is monotone; a colour's sigmoid may round to 0, so a colour looks up).
  bool reflects(float lambda) const {
    return (!colour && scale * spectrum->minimum() > 0.0f) || (*this)(lambda) > 0.0f;
  }
};

// A scalar parameter's texture: value × texel (no texture: the value).
struct ScalarTexture {
  std::shared_ptr<const Texture> texture;  // one channel, values in [0, 1]
  float at(float value, const TexturePoint& p) const { return texture ? value * texture->scalar(p) : value; }
};

// A reflectance's texture: one channel scales the spectrum, three give it a colour (JH19).
struct ReflectanceTexture {
  std::shared_ptr<const Texture> texture;  // one or three channels, values in [0, 1]
  HitReflectance at(const Spectrum& spectrum, const TexturePoint& p) const {
    HitReflectance r{&spectrum};
    if (!texture) return r;
    if (texture->channels() == 3) {
      r.colour = true;
      r.sigmoid = rgbToSigmoid(texture->rgb(p));
    } else {
      r.scale = texture->scalar(p);
    }
    return r;
  }
};

// The set textures among `fields` (ScalarTexture, ReflectanceTexture), for Material::textures().
template <class... Fields>
std::vector<const Texture*> setTextures(const Fields&... fields) {
  std::vector<const Texture*> out;
  ((fields.texture ? out.push_back(fields.texture.get()) : void()), ...);
  return out;
}

// The textures of a GGX roughness: factors on α_x and α_y (one texture for both: the same twice).
struct AlphaTexture {
  ScalarTexture x, y;
  bool any() const { return x.texture || y.texture; }
};

// A GGX distribution with its α multiplied by the textures at p, at least kMinAlpha (ggx.h).
inline Ggx texturedGgx(const Ggx& ggx, const AlphaTexture& alpha, const TexturePoint& p) {
  if (!alpha.any()) return ggx;
  return Ggx(std::max(alpha.x.at(ggx.alphaX(), p), kMinAlpha), std::max(alpha.y.at(ggx.alphaY(), p), kMinAlpha));
}

}  // namespace kasha
