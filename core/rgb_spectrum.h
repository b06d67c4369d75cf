#pragma once
// RGB → reflectance spectrum after Jakob & Hanika 2019 ("A Low-Dimensional Function Space for
// Efficient Spectral Upsampling", JH19): a reflectance is the sigmoid of a quadratic in λ,
//   s(λ) = S(c0·t² + c1·t + c2),  S(x) = ½ + x / (2√(1 + x²)),  t = (λ − 360 nm) / 470 nm,
// which lies in [0, 1] at every λ, is smooth, and has at most one extremum. The three
// coefficients of a linear sRGB colour are those whose spectrum, lit by D65 and seen by the CIE
// 1931 observer (core/color.h), gives back that colour (white (1, 1, 1) is the reflectance 1).
// They are fitted by Gauss–Newton on a table of colours (JH19 §4: the largest component z and
// the two others divided by it, z spaced densely near 0 and 1), once per process, and
// interpolated trilinearly; fitRgbSigmoid() solves one colour exactly.
//
// Outside 360–830 nm (a UV scene's range) the polynomial continues: an RGB colour says nothing
// there, the spectrum only stays bounded and smooth.
#include <array>
#include <optional>

#include "core/math.h"
#include "core/spectrum.h"

namespace kasha {

struct RgbSigmoid {
  std::array<float, 3> c{0.0f, 0.0f, 0.0f};  // c0, c1, c2 of the quadratic in t; ±inf in c2: 0 or 1
  // s(λ) in [0, 1], λ in nm.
  float operator()(float lambda) const;
};

// The table's resolution per axis (JH19 use 64; the trilinear error at 32 is tested).
constexpr int kRgbTableResolution = 32;

// The reflectance spectrum of a linear sRGB colour with components in [0, 1] (outside: clamped;
// non-finite: 0), from the table (within 0.01 per component; tested). Builds the table on first
// use: about 0.5 s on two cores.
RgbSigmoid rgbToSigmoid(Vec3 linearSrgb);

// The same, refined to the exact fit (within 1e-6 where one exists), tabulated every nanometre
// over `range` as a Spectrum, for fields that take any spectrum (`{"type": "rgb", "value":
// [r, g, b]}`, Mitsuba's <rgb>): the one entry point for importers.
Spectrum rgbToSpectrum(Vec3 linearSrgb, const WavelengthRange& range);

// Solves one colour by damped Gauss–Newton from `start`, to |RGB error| < 1e-6 per component.
// nullopt if it does not converge in `maxIterations` (colours on the gamut's edge, such as pure
// primaries, need infinite coefficients).
std::optional<RgbSigmoid> fitRgbSigmoid(Vec3 linearSrgb, RgbSigmoid start, int maxIterations = 50);

// The linear sRGB colour of a reflectance under D65 (the forward model of the fit), by the
// 1 nm CIE tables: M_sRGB · ∫ (x̄, ȳ, z̄)·D65·s dλ / ∫ ȳ·D65 dλ over 360–830 nm.
// Independent of the fit's own quadrature (5 nm, on the sigmoid): tests compare the two.
Vec3 reflectanceToLinearSrgb(const Spectrum& s);

}  // namespace kasha
