#pragma once
// Colorimetry: the CIE 1931 2° standard observer and conversion of XYZ to linear sRGB.
#include "core/math.h"
#include "core/spectrum.h"

namespace kasha {

// x̄, ȳ, z̄ (CIE 018:2019 tables, 360–830 nm, 1 nm), zero outside their table.
struct Observer {
  Spectrum xbar, ybar, zbar;
  float yIntegral;  // ∫ȳ dλ over 360–830 nm

  // The film's normalisation: XYZ = ∫ (x̄, ȳ, z̄)(λ) L(λ) dλ / ∫ȳ dλ, so a constant radiance of 1
  // has Y = 1. One wavelength sample contributes weight(λ)·L/p(λ).
  Vec3 weight(float lambda) const { return Vec3(xbar(lambda), ybar(lambda), zbar(lambda)) / yIntegral; }
  // The film's XYZ of radiance L over the range: ∫_range weight(λ)·L(λ) dλ, exact up to rounding
  // (both are piecewise linear, so Simpson's rule is exact between their merged knots).
  Vec3 xyz(const Spectrum& L, WavelengthRange range) const;

  static const Observer& cie1931();
};

// IEC 61966-2-1 matrix, D65 white: linear sRGB from XYZ.
Vec3 xyzToLinearSrgb(const Vec3& xyz);
// The sRGB transfer function (gamma) for one channel in [0, 1].
float srgbEncode(float linear);
// Its inverse (IEC 61966-2-1): the linear value of an encoded one in [0, 1].
float srgbDecode(float encoded);

}  // namespace kasha
