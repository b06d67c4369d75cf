#pragma once
// A spectral function of wavelength (nm). Every spectrum is held as a piecewise-linear function:
// tabulated data as given, analytic shapes (Gaussian, blackbody) tabulated finely, bands as steps.
// Evaluation, exact integrals and exact importance sampling all use this one representation, so
// what is rendered and what the closed-form tests integrate are the same function.
#include <algorithm>
#include <string>
#include <utility>
#include <vector>

namespace kasha {

// The wavelengths a scene transports, in nm. Default: the visible range of the CIE observer.
struct WavelengthRange {
  float min = 360.0f;
  float max = 830.0f;
  float width() const { return max - min; }
  bool contains(float l) const { return l >= min && l <= max; }
};

class Spectrum {
 public:
  Spectrum() : Spectrum(constant(0.0f)) {}

  static Spectrum constant(float value);
  // Knots sorted by wavelength; a repeated wavelength makes a step (right-continuous). Values
  // outside the knots are the end values (constant extrapolation).
  static Spectrum piecewiseLinear(std::vector<float> lambdas, std::vector<float> values);
  // value on [lo, hi), zero elsewhere.
  static Spectrum box(float lo, float hi, float value);
  // Gaussian with the given centre and full width at half maximum, peak value `peak`,
  // tabulated at FWHM/100 over centre ± 3 FWHM (zero beyond).
  static Spectrum gaussian(float centre, float fwhm, float peak = 1.0f);
  // Planck's law at `kelvin`, normalised to 1 at its maximum over 300–830 nm, tabulated per nm.
  static Spectrum blackbody(float kelvin);

  // Σ w_k·s_k, exact: piecewise linear on the union of all knots, steps kept.
  static Spectrum weightedSum(const std::vector<std::pair<float, const Spectrum*>>& terms);

  float operator()(float lambda) const {
    // Inline: the lookup of equally spaced knots, the common case in the hot loops.
    size_t i;
    float t;
    if (uniformSegment(lambda, i, t)) return y_[i] + t * (y_[i + 1] - y_[i]);
    return evaluateByKnotSearch(lambda);
  }
  // Where λ lies among equally spaced knots: the segment [x_i, x_i+1] and the fraction t along it;
  // false elsewhere (operator() then searches the knots). Spectra with the same knots share it.
  bool uniformSegment(float lambda, size_t& i, float& t) const {
    if (!(uniformStep_ > 0.0f && lambda > x_[i0_] && lambda < x_[i1_])) return false;
    i = std::min(i0_ + size_t((lambda - x_[i0_]) / uniformStep_), i1_ - 1);
    t = (lambda - x_[i]) / (x_[i + 1] - x_[i]);
    return true;
  }
  // Limit from the left (differs from operator() only at a step).
  float leftLimit(float lambda) const;
  // ∫ over [lo, hi] of this spectrum, exact for the piecewise-linear representation.
  float integral(float lo, float hi) const;
  float integral(const WavelengthRange& r) const { return integral(r.min, r.max); }
  float maxValue(float lo, float hi) const;
  float minValue(float lo, float hi) const;
  // The infimum of the values over all wavelengths: the least knot value (the function is
  // piecewise linear between knots and constant beyond them; at a step it may be a left limit).
  float minimum() const { return minimum_; }
  Spectrum scaled(float s) const;
  // Zero outside [first knot, last knot] instead of constant extrapolation.
  Spectrum zeroOutside() const;

  const std::vector<float>& lambdas() const { return x_; }
  const std::vector<float>& values() const { return y_; }

 private:
  Spectrum(std::vector<float> x, std::vector<float> y);
  // operator() where the fast path does not apply: a binary search of the knots.
  float evaluateByKnotSearch(float lambda) const;
  std::vector<float> x_, y_;
  // O(1) lookup where the knots are equally spaced: between knots i0_ and i1_ (the longest such
  // run from the first knot, or from the second where zeroOutside() duplicated the first) with
  // spacing uniformStep_ > 0.
  float uniformStep_ = 0.0f;
  size_t i0_ = 0, i1_ = 0;
  float minimum_ = 0.0f;
};

}  // namespace kasha
