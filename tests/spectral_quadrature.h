#pragma once
// Quadrature of spectra on the wavelength range and the closed forms of docs/validation.md §1–2 built
// from it: shared by the closed-form tests (tests/closed_form_support.h) and the merge-bias bench
// (bench/merge_bias/), so it needs no test framework.
#include <functional>
#include <vector>

#include "core/color.h"
#include "materials/jung_bbrrdf.h"

namespace kasha::test {

using Fn = std::function<double(double)>;

// Midpoint quadrature on a 0.05 nm grid aligned with whole nanometres, so steps of the box spectra
// and knots of the 1 nm CIE tables fall on cell boundaries.
constexpr double kStep = 0.05;

struct Grid {
  std::vector<double> x;
  explicit Grid(WavelengthRange r) {
    for (double l = r.min + 0.5 * kStep; l < r.max; l += kStep) x.push_back(l);
  }
  double integrate(const std::vector<double>& f) const {
    double s = 0.0;
    for (double v : f) s += v * kStep;
    return s;
  }
  std::vector<double> sample(const Fn& f) const {
    std::vector<double> v(x.size());
    for (size_t i = 0; i < x.size(); ++i) v[i] = f(x[i]);
    return v;
  }
};

// XYZ of a radiance spectrum given on the grid, in the film's normalisation.
inline Vec3 toXyz(const Grid& g, const std::vector<double>& L) {
  const Observer& o = Observer::cie1931();
  double X = 0, Y = 0, Z = 0;
  for (size_t i = 0; i < g.x.size(); ++i) {
    X += o.xbar(float(g.x[i])) * L[i] * kStep;
    Y += o.ybar(float(g.x[i])) * L[i] * kStep;
    Z += o.zbar(float(g.x[i])) * L[i] * kStep;
  }
  return Vec3(float(X / o.yIntegral), float(Y / o.yIntegral), float(Z / o.yIntegral));
}

// Applies the furnace transport operator once to a uniform isotropic radiance L (Jung18 eq. 4
// integrated over the hemisphere): (T L)(λ) = (1 − c·a)·r·L(λ) + Q·e(λ)·∫ c·a·L dλ.
inline std::vector<double> transport(const Grid& g, const JungBbrrdf& m, const std::vector<double>& L) {
  std::vector<double> ca = g.sample([&](double l) { return m.c() * m.a(float(l)); });
  std::vector<double> absorbed(g.x.size());
  for (size_t i = 0; i < L.size(); ++i) absorbed[i] = ca[i] * L[i];
  const double A = g.integrate(absorbed);
  std::vector<double> out(L.size());
  for (size_t i = 0; i < L.size(); ++i)
    out[i] = (1.0 - ca[i]) * m.r(float(g.x[i])) * L[i] + m.q() * m.e(float(g.x[i])) * A;
  return out;
}

// docs/validation.md §2 at normal incidence: the radiance a diffuse fluorescent surface reflects under the
// irradiance E(λ), L_o = [(1 − c·a)·r·E + Q·e·∫ c·a·E dλ] / π (times cos θ for oblique light).
inline std::vector<double> singleScattering(const Grid& g, const JungBbrrdf& m, const Fn& E) {
  const double absorbed = g.integrate(g.sample([&](double l) { return m.c() * m.a(float(l)) * E(l); }));
  return g.sample([&](double l) {
    const float lf = float(l);
    return ((1.0 - m.c() * m.a(lf)) * m.r(lf) * E(l) + m.q() * m.e(lf) * absorbed) / kPi;
  });
}

// docs/validation.md §1: L = [L_e + Q·e·K] / D, D = 1 − (1 − c·a)·r, K = A / (1 − Q·B).
inline std::vector<double> furnaceClosedForm(const Grid& g, const JungBbrrdf& m, const Fn& Le) {
  std::vector<double> D = g.sample([&](double l) { return 1.0 - (1.0 - m.c() * m.a(float(l))) * m.r(float(l)); });
  std::vector<double> fa(g.x.size()), fb(g.x.size());
  for (size_t i = 0; i < g.x.size(); ++i) {
    const double ca = m.c() * m.a(float(g.x[i]));
    fa[i] = ca * Le(g.x[i]) / D[i];
    fb[i] = ca * m.e(float(g.x[i])) / D[i];
  }
  const double K = g.integrate(fa) / (1.0 - m.q() * g.integrate(fb));
  std::vector<double> L(g.x.size());
  for (size_t i = 0; i < g.x.size(); ++i) L[i] = (Le(g.x[i]) + m.q() * m.e(float(g.x[i])) * K) / D[i];
  return L;
}

}  // namespace kasha::test
