#pragma once
// Emission spectra of linear sRGB colours, after pbrt-v4's RGBIlluminantSpectrum (Pharr, Jakob &
// Humphreys, "Physically Based Rendering", 4th ed., §4.6.6): L(λ) = m·s(λ)·D65(λ)/Y_D65 with
// m = 2·max(r, g, b) and s the Jakob–Hanika reflectance of rgb/m (core/rgb_spectrum.h), whose
// colour under D65 is rgb/m. So L has the colour rgb on kasha's film (XYZ normalised by ∫ȳ):
// (1, 1, 1) is D65 with Y = 1. Used by Mitsuba's <rgb> radiance and by the envmap's texels.
#include "core/rgb_spectrum.h"

namespace kasha {

struct RgbIlluminant {
  float m = 0.0f;  // 2·max(r, g, b); 0 for black
  RgbSigmoid s;
  // L(λ), W·m⁻²·sr⁻¹·nm⁻¹ up to the scene's unit.
  float operator()(float lambda) const;
  // m·s(λ), L without D65: the colour as an unbounded reflectance (pbrt-v4's RGBUnboundedSpectrum),
  // which modulates another emitter's spectrum (a textured spot light's).
  float modulation(float lambda) const { return m > 0.0f ? m * s(lambda) : 0.0f; }
};

// From the coefficient table (fast; within the table's tolerance of the colour). Components must
// be finite and ≥ 0.
RgbIlluminant rgbIlluminant(Vec3 linearSrgb);

// The same with the exact fit, tabulated every nm over `range`.
Spectrum rgbIlluminantSpectrum(Vec3 linearSrgb, const WavelengthRange& range);

// D65(λ)/Y_D65: the CIE D65 illuminant scaled to Y = 1 on kasha's film.
float unitD65(float lambda);

}  // namespace kasha
