#pragma once
// Material parameters that vary over a surface: an image texture (core/texture.h) read at the
// hit's texture coordinates, multiplying the material's value there. A reflectance texture has
// one channel (a factor on the spectrum) or three (a linear sRGB colour whose Jakob–Hanika
// spectrum, core/rgb_spectrum.h, multiplies the spectrum: with the spectrum 1, the colour).
// Without a texture the value is the material's own, unchanged bit for bit (×1).
#include <algorithm>
#include <memory>

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
  std::shared_ptr<const ImageTexture> image;  // one channel, values in [0, 1]
  float at(float value, Vec2 uv) const { return image ? value * image->scalar(uv) : value; }
};

// A reflectance's texture: one channel scales the spectrum, three give it a colour (JH19).
struct ReflectanceTexture {
  std::shared_ptr<const ImageTexture> image;  // one or three channels, values in [0, 1]
  HitReflectance at(const Spectrum& spectrum, Vec2 uv) const {
    HitReflectance r{&spectrum};
    if (!image) return r;
    if (image->channels() == 3) {
      r.colour = true;
      r.sigmoid = rgbToSigmoid(image->rgb(uv));
    } else {
      r.scale = image->scalar(uv);
    }
    return r;
  }
};

// A GGX distribution with both α multiplied by the texture at uv, at least kMinAlpha (ggx.h).
inline Ggx texturedGgx(const Ggx& ggx, const ScalarTexture& alpha, Vec2 uv) {
  if (!alpha.image) return ggx;
  const float s = alpha.image->scalar(uv);
  return Ggx(std::max(ggx.alphaX() * s, kMinAlpha), std::max(ggx.alphaY() * s, kMinAlpha));
}

}  // namespace kasha
