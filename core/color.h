#pragma once
// Colorimetry: the CIE 1931 2° standard observer and conversion of XYZ to linear sRGB.
#include "core/math.h"
#include "core/spectrum.h"

namespace kasha {

// The luminance Y of a linear sRGB colour (ITU-R BT.709 primaries).
inline float luminance(const Vec3& rgb) { return 0.2126f * rgb.x + 0.7152f * rgb.y + 0.0722f * rgb.z; }

// x̄, ȳ, z̄ (CIE 018:2019 tables, 360–830 nm, 1 nm), zero outside their table.
struct Observer {
  Spectrum xbar, ybar, zbar;
  float yIntegral;  // ∫ȳ dλ over 360–830 nm

  bool sharedKnots = false;  // x̄, ȳ, z̄ tabulated at the same wavelengths: one lookup finds all three

  // The film's normalisation: XYZ = ∫ (x̄, ȳ, z̄)(λ) L(λ) dλ / ∫ȳ dλ, so a constant radiance of 1
  // has Y = 1. One wavelength sample contributes weight(λ)·L/p(λ).
  Vec3 weight(float lambda) const {
    size_t i;
    float t;
    if (sharedKnots && ybar.uniformSegment(lambda, i, t)) {
      const auto at = [&](const Spectrum& s) { return s.values()[i] + t * (s.values()[i + 1] - s.values()[i]); };
      return Vec3(at(xbar), at(ybar), at(zbar)) / yIntegral;
    }
    return Vec3(xbar(lambda), ybar(lambda), zbar(lambda)) / yIntegral;
  }
  // The film's XYZ of radiance L over the range: ∫_range weight(λ)·L(λ) dλ, exact up to rounding
  // (both are piecewise linear, so Simpson's rule is exact between their merged knots).
  Vec3 xyz(const Spectrum& L, WavelengthRange range) const;

  static const Observer& cie1931();
};

// IEC 61966-2-1 matrix, D65 white: linear sRGB from XYZ.
Vec3 xyzToLinearSrgb(const Vec3& xyz);
// The sRGB transfer function (gamma) for one channel in [0, 1].
float srgbEncode(float linear);
// The inverse: an sRGB-encoded value in [0, 1] to linear (IEC 61966-2-1, the sRGB transfer function).
float srgbDecode(float encoded);

}  // namespace kasha
