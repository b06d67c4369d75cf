#pragma once
// A checkerboard (Mitsuba 3 docs: checkerboard): two values in the 2×2 checker over the unit
// square of texture coordinates, repeated. With (s, t) = to_uv(u, v) − floor(to_uv(u, v)), the
// point reads color0 where s and t are both ≤ ½ or both > ½, and color1 elsewhere. The values
// are numbers (one channel) or linear sRGB colours (three: a number then stands for its grey).
#include "core/texture.h"

namespace kasha {

class CheckerboardTexture : public Texture {
 public:
  // Throws std::invalid_argument if channels is not 1 or 3 or a value lies outside [0, 1].
  CheckerboardTexture(Vec3 color0, Vec3 color1, int channels, UvTransform toUv = {});
  int channels() const override { return channels_; }
  float scalar(const TexturePoint& p) const override { return at(p.uv).x; }
  Vec3 rgb(const TexturePoint& p) const override { return at(p.uv); }

 private:
  Vec3 at(Vec2 uv) const;
  Vec3 color0_, color1_;
  int channels_;
  UvTransform toUv_;
};

}  // namespace kasha
