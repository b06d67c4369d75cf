#include "core/checkerboard_texture.h"

#include <cmath>
#include <stdexcept>

namespace kasha {

CheckerboardTexture::CheckerboardTexture(Vec3 color0, Vec3 color1, int channels, UvTransform toUv)
    : color0_(color0), color1_(color1), channels_(channels), toUv_(toUv) {
  if (channels != 1 && channels != 3) throw std::invalid_argument("checkerboard: channels must be 1 or 3");
  for (const Vec3& c : {color0, color1})
    for (int k = 0; k < 3; ++k)
      if (!(c[k] >= 0.0f && c[k] <= 1.0f)) throw std::invalid_argument("checkerboard: a value lies outside [0, 1]");
}

Vec3 CheckerboardTexture::at(Vec2 uv) const {
  const Vec2 t = toUv_(uv);
  const Vec2 f = t - glm::floor(t);  // non-finite uv give NaN, which is not > ½: color0
  return (f.x > 0.5f) == (f.y > 0.5f) ? color0_ : color1_;
}

}  // namespace kasha
