#include "core/rgb_illuminant.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/color.h"
#include "core/spectrum_presets.h"

namespace kasha {
namespace {

// D65 with Y = ∫ȳ·D65 dλ / ∫ȳ dλ = 1 (1 nm sums over the observer's 360–830 nm).
const Spectrum& unitD65Spectrum() {
  static const Spectrum s = [] {
    const Spectrum d65 = *presetSpectrum("D65");
    double y = 0.0;
    for (int nm = 360; nm <= 830; ++nm) y += double(Observer::cie1931().weight(float(nm)).y) * d65(float(nm));
    return d65.scaled(float(1.0 / y));
  }();
  return s;
}

}  // namespace

float unitD65(float lambda) { return unitD65Spectrum()(lambda); }

float RgbIlluminant::operator()(float lambda) const { return modulation(lambda) * unitD65(lambda); }

RgbIlluminant rgbIlluminant(Vec3 rgb) {
  const float m = 2.0f * std::max({rgb.x, rgb.y, rgb.z});
  if (!(m > 0.0f)) return {};
  return {m, rgbToSigmoid(rgb / m)};
}

Spectrum rgbIlluminantSpectrum(Vec3 rgb, const WavelengthRange& range) {
  const float m = 2.0f * std::max({rgb.x, rgb.y, rgb.z});
  if (!(m > 0.0f)) return Spectrum::constant(0.0f);
  const Spectrum s = rgbToSpectrum(rgb / m, range);
  std::vector<float> wl, v;
  for (float nm = std::floor(range.min); nm <= std::ceil(range.max); nm += 1.0f) {
    wl.push_back(nm);
    v.push_back(m * s(nm) * unitD65(nm));
  }
  return Spectrum::piecewiseLinear(std::move(wl), std::move(v));
}

}  // namespace kasha
