#include "materials/zhdanov_extraction.h"

#include <cmath>

#include "core/error.h"

namespace kasha {
namespace {

const auto nm = formatNm;

}  // namespace

ZhdanovFit extractZhdanov(const ExtractionInput& input) {
  const BispectralData& s = input.sample;
  const size_t nIn = s.in.size(), nOut = s.out.size();
  if (input.etalon && (input.etalon->in != s.in || input.etalon->out != s.out))
    throw InputError(input.etalon->source, "", "its wavelength grids differ from those of " + s.source);
  const auto near = [&](size_t o, size_t i) { return std::abs(s.out[o] - s.in[i]) <= input.epsilon; };
  const auto stokes = [&](size_t o, size_t i) { return s.out[o] - s.in[i] > input.epsilon; };

  ZhdanovFit fit;
  fit.in = s.in;
  fit.out = s.out;
  fit.passive.assign(nIn, 0.0f);
  fit.excitation.assign(nIn, 0.0f);
  fit.emission.assign(nOut, 0.0f);
  fit.passiveMeasured.assign(nIn, false);
  const std::vector<float> dOut = bandWidths(s.out), dIn = bandWidths(s.in);
  std::vector<double> F(nIn * nOut, 0.0);  // F[o * nIn + i], per nm
  for (size_t i = 0; i < nIn; ++i) {
    // Calibration R̄_e (Zhdanov eqs. 6–7); 1 without an etalon.
    double cal = 1.0;
    if (input.etalon) {
      double sum = 0.0;
      for (size_t o = 0; o < nOut; ++o)
        if (near(o, i)) sum += std::max(0.0f, input.etalon->at(o, i));
      const float rho = input.etalonReflectance(s.in[i]);
      cal = rho > 0.0f ? sum / rho : 0.0;
    }
    double passive = 0.0, anything = 0.0;
    bool measured = false;
    for (size_t o = 0; o < nOut; ++o) {
      const double v = std::max(0.0f, s.at(o, i));
      anything += v;
      if (near(o, i)) {
        passive += v;
        measured = true;
      }
    }
    if (!measured && input.etalon) {
      // No output within ε of λ_i: neither the etalon nor the passive part can be measured there.
      if (anything > 0.0) fit.uncalibrated.push_back(s.in[i]);
      continue;
    }
    if (!(cal > 0.0)) {
      if (anything > 0.0)
        throw InputError(input.etalon->source, "ex_" + nm(s.in[i]),
                         "the etalon gives no signal within ±" + std::to_string(input.epsilon) +
                             " nm of the diagonal (or its reflectance is 0), so the sample cannot be calibrated there");
      continue;
    }
    fit.passive[i] = float(passive / cal);  // eq. 7
    fit.passiveMeasured[i] = measured;
    double a = 0.0;
    for (size_t o = 0; o < nOut; ++o) {
      const double g = std::max(0.0f, s.at(o, i)) / cal;
      if (!stokes(o, i) || g <= input.noiseFloor) continue;
      F[o * nIn + i] = g / dOut[o];  // eq. 8
      a += g;
    }
    fit.excitation[i] = float(a);  // eq. 9: A = ∫F dλ_o
  }
  // Eq. 9: E(λ_o) = ∫F(λ_o; λ_i) dλ_i / ∫A(λ_i) dλ_i over the inputs that can reach λ_o.
  for (size_t o = 0; o < nOut; ++o) {
    double num = 0.0, den = 0.0;
    for (size_t i = 0; i < nIn; ++i)
      if (stokes(o, i)) {
        num += F[o * nIn + i] * dIn[i];
        den += fit.excitation[i] * dIn[i];
      }
    fit.emission[o] = den > 0.0 ? float(num / den) : 0.0f;
  }
  double mass = 0.0;
  for (size_t o = 0; o < nOut; ++o) mass += fit.emission[o] * dOut[o];
  if (mass > 0.0)
    for (float& e : fit.emission) e = float(e / mass);  // eq. 4: ∫E = 1
  // Residual of the factorisation (eq. 3) on the Stokes cells, and the model's unmeasured part.
  double err = 0.0, norm = 0.0, outside = 0.0, total = 0.0;
  for (size_t i = 0; i < nIn; ++i)
    for (size_t o = 0; o < nOut; ++o) {
      const double model = double(fit.emission[o]) * fit.excitation[i];
      total += model * dOut[o];
      if (!stokes(o, i)) {
        outside += model * dOut[o];
        continue;
      }
      const double f = F[o * nIn + i];
      err += (f - model) * (f - model);
      norm += f * f;
    }
  fit.residual = norm > 0.0 ? std::sqrt(err / norm) : 0.0;
  fit.unmeasuredFraction = total > 0.0 ? outside / total : 0.0;
  return fit;
}

}  // namespace kasha
