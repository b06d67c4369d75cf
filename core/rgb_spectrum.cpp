#include "core/rgb_spectrum.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <thread>
#include <vector>

#include "core/color.h"
#include "core/spectrum_presets.h"

namespace kasha {
namespace {

constexpr double kLambdaMin = 360.0, kLambdaSpan = 470.0;  // t = (λ − 360) / 470
constexpr double kFitStep = 5.0;                           // nm between the fit's quadrature nodes
constexpr int kFitNodes = int(kLambdaSpan / kFitStep) + 1;


// The fit's forward model: RGB(c) = Σ_k W_k·S(c0·t_k² + c1·t_k + c2), the trapezoid rule over
// 360–830 nm every 5 nm with W_k = M_sRGB·(x̄, ȳ, z̄)·D65 / ∫ ȳ·D65, so that S ≡ 1 gives the white
// (1, 1, 1) up to the quadrature and the matrix.
struct FitNodes {
  std::array<double, kFitNodes> t;
  std::array<std::array<double, 3>, kFitNodes> w;

  FitNodes() {
    const Observer& obs = Observer::cie1931();
    const Spectrum d65 = *presetSpectrum("D65");
    double yNorm = 0.0;
    std::array<Vec3, kFitNodes> xyz;
    for (int k = 0; k < kFitNodes; ++k) {
      const float lambda = float(kLambdaMin + kFitStep * k);
      const double trapezoid = (k == 0 || k == kFitNodes - 1) ? 0.5 : 1.0;
      xyz[k] = Vec3(obs.xbar(lambda), obs.ybar(lambda), obs.zbar(lambda)) * float(d65(lambda) * trapezoid);
      yNorm += double(xyz[k].y);
      t[k] = kFitStep * k / kLambdaSpan;
    }
    for (int k = 0; k < kFitNodes; ++k) {
      const Vec3 rgb = xyzToLinearSrgb(xyz[k]);
      for (int i = 0; i < 3; ++i) w[k][i] = double(rgb[i]) / yNorm;
    }
  }
};

const FitNodes& fitNodes() {
  static const FitNodes nodes;
  return nodes;
}

using Vec3d = std::array<double, 3>;
using Mat3d = std::array<Vec3d, 3>;

// RGB(c) − target and its Jacobian ∂RGB/∂c; returns the largest |component| of the residual.
double residual(const Vec3d& c, const Vec3d& target, Vec3d& r, Mat3d& jacobian) {
  const FitNodes& n = fitNodes();
  r = {-target[0], -target[1], -target[2]};
  jacobian = {};
  for (int k = 0; k < kFitNodes; ++k) {
    const double t = n.t[k], x = (c[0] * t + c[1]) * t + c[2];
    // JH19 §3: S(x) = ½ + x / (2√(1 + x²)), S'(x) = 1 / (2 (1 + x²)^{3/2})
    const double q = 1.0 + x * x, root = std::sqrt(q);
    const double s = 0.5 + x / (2.0 * root), ds = 0.5 / (q * root);
    const Vec3d dx = {t * t, t, 1.0};
    for (int i = 0; i < 3; ++i) {
      r[i] += n.w[k][i] * s;
      for (int j = 0; j < 3; ++j) jacobian[i][j] += n.w[k][i] * ds * dx[j];
    }
  }
  return std::max({std::abs(r[0]), std::abs(r[1]), std::abs(r[2])});
}

// Solves A·x = b for a 3×3 A by Cramer's rule; false if A is singular.
bool solve3(const Mat3d& a, const Vec3d& b, Vec3d& x) {
  const auto det = [](const Mat3d& m) {
    return m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
           m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
  };
  const double d = det(a);
  if (!(std::abs(d) > 1e-300)) return false;
  for (int col = 0; col < 3; ++col) {
    Mat3d m = a;
    for (int row = 0; row < 3; ++row) m[row][col] = b[row];
    x[col] = det(m) / d;
  }
  return true;
}

constexpr double kFitTolerance = 1e-6;


// Levenberg–Marquardt-damped Gauss–Newton on the three RGB residuals; returns the largest
// remaining residual component and leaves the best coefficients in c.
double fit(const Vec3d& target, Vec3d& c, int maxIterations) {
  Vec3d r;
  Mat3d jac;
  double err = residual(c, target, r, jac), mu = 1e-6;
  for (int it = 0; it < maxIterations && err > kFitTolerance; ++it) {
    Mat3d normal{};
    Vec3d rhs{};
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) {
        rhs[i] -= jac[j][i] * r[j];
        for (int k = 0; k < 3; ++k) normal[i][j] += jac[k][i] * jac[k][j];
      }
    bool improved = false;
    for (int tries = 0; tries < 30 && !improved; ++tries, mu *= 10.0) {
      Mat3d damped = normal;
      for (int i = 0; i < 3; ++i) damped[i][i] += mu * (normal[i][i] + 1e-12);
      Vec3d step;
      if (!solve3(damped, rhs, step)) continue;
      const Vec3d next = {c[0] + step[0], c[1] + step[1], c[2] + step[2]};
      Vec3d rNext;
      Mat3d jacNext;
      const double errNext = residual(next, target, rNext, jacNext);
      if (errNext < err) {
        c = next;
        err = errNext;
        r = rNext;
        jac = jacNext;
        improved = true;
      }
    }
    if (!improved) break;
    mu = std::max(mu * 1e-3, 1e-12);
  }
  return err;
}

// JH19 §4: for each largest component l, the colour z·(1, x, y) (rotated so that z sits at l),
// x and y uniform in [0, 1], z at smoothstep(smoothstep(k / (res − 1))).
struct RgbTable {
  static constexpr int kRes = kRgbTableResolution;
  std::array<float, kRes> z;
  std::vector<std::array<float, 3>> coeffs = std::vector<std::array<float, 3>>(size_t(3) * kRes * kRes * kRes);

  static size_t index(int l, int k, int j, int i) { return ((size_t(l) * kRes + k) * kRes + j) * kRes + i; }

  RgbTable() {
    const auto smoothstep = [](double x) { return x * x * (3.0 - 2.0 * x); };
    for (int k = 0; k < kRes; ++k) z[k] = float(smoothstep(smoothstep(double(k) / (kRes - 1))));
    fitNodes();  // before the threads
    // One column (l, x, y) per task, walked outwards in z from a mid-grey start so that each fit
    // starts from its neighbour's solution (JH19 §4).
    std::atomic<int> next{0};
    const auto fitColumn = [&](int column) {
      const int l = column / (kRes * kRes), j = (column / kRes) % kRes, i = column % kRes;
      const int start = kRes / 5;
      Vec3d c = {0.0, 0.0, 0.0}, atStart{};
      const auto fitAt = [&](int k) {
        // z = 0 is black, handled by rgbToSigmoid; its row holds the next row's fit.
        const double zk = double(z[std::max(k, 1)]);
        Vec3d target;
        target[l] = zk;
        target[(l + 1) % 3] = zk * i / (kRes - 1);
        target[(l + 2) % 3] = zk * j / (kRes - 1);
        fit(target, c, 100);
        coeffs[index(l, k, j, i)] = {float(c[0]), float(c[1]), float(c[2])};
      };
      for (int k = start; k < kRes; ++k) {
        fitAt(k);
        if (k == start) atStart = c;
      }
      c = atStart;
      for (int k = start - 1; k >= 0; --k) fitAt(k);
    };
    std::vector<std::thread> workers(std::max(1u, std::thread::hardware_concurrency()));
    for (std::thread& w : workers)
      w = std::thread([&] {
        for (int column; (column = next++) < 3 * kRes * kRes;) fitColumn(column);
      });
    for (std::thread& w : workers) w.join();
  }
};

const RgbTable& rgbTable() {
  static const RgbTable table;
  return table;
}

}  // namespace

float RgbSigmoid::operator()(float lambda) const {
  const float t = (lambda - float(kLambdaMin)) / float(kLambdaSpan);
  const float x = (c[0] * t + c[1]) * t + c[2];
  if (std::isinf(x)) return x > 0.0f ? 1.0f : 0.0f;
  return std::clamp(0.5f + x / (2.0f * std::sqrt(1.0f + x * x)), 0.0f, 1.0f);
}

RgbSigmoid rgbToSigmoid(Vec3 rgb) {
  for (int i = 0; i < 3; ++i) rgb[i] = std::isfinite(rgb[i]) ? std::clamp(rgb[i], 0.0f, 1.0f) : 0.0f;
  const int l = rgb.x >= rgb.y && rgb.x >= rgb.z ? 0 : (rgb.y >= rgb.z ? 1 : 2);
  const float zv = rgb[l];
  if (zv == 0.0f) return RgbSigmoid{{0.0f, 0.0f, -kInf}};  // black
  const RgbTable& tab = rgbTable();
  constexpr int R = RgbTable::kRes;
  const auto cell = [](float v, int& idx) {
    const float f = v * (R - 1);
    idx = std::min(int(f), R - 2);
    return f - float(idx);
  };
  int i, j;
  const float dx = cell(rgb[(l + 1) % 3] / zv, i), dy = cell(rgb[(l + 2) % 3] / zv, j);
  const int k = std::clamp(int(std::upper_bound(tab.z.begin(), tab.z.end(), zv) - tab.z.begin()) - 1, 0, R - 2);
  const float dz = std::clamp((zv - tab.z[k]) / (tab.z[k + 1] - tab.z[k]), 0.0f, 1.0f);
  RgbSigmoid out;
  for (int corner = 0; corner < 8; ++corner) {
    const int a = corner & 1, b = (corner >> 1) & 1, e = corner >> 2;
    const float w = (a ? dx : 1.0f - dx) * (b ? dy : 1.0f - dy) * (e ? dz : 1.0f - dz);
    const std::array<float, 3>& c = tab.coeffs[RgbTable::index(l, k + e, j + b, i + a)];
    for (int n = 0; n < 3; ++n) out.c[n] += w * c[n];
  }
  return out;
}

Spectrum rgbToSpectrum(Vec3 rgb, const WavelengthRange& range) {
  RgbSigmoid s = rgbToSigmoid(rgb);
  // One colour: polish the table's interpolated coefficients into the exact fit where one exists.
  const Vec3 clamped = glm::clamp(rgb, Vec3(0.0f), Vec3(1.0f));
  if (std::isfinite(s.c[2]) && clamped == rgb)
    if (const auto exact = fitRgbSigmoid(rgb, s, 20)) s = *exact;
  std::vector<float> x, y;
  for (float l = std::floor(range.min); l < range.max + 1.0f; l += 1.0f) {
    x.push_back(l);
    y.push_back(s(l));
  }
  return Spectrum::piecewiseLinear(std::move(x), std::move(y));
}

std::optional<RgbSigmoid> fitRgbSigmoid(Vec3 rgb, RgbSigmoid start, int maxIterations) {
  Vec3d c = {start.c[0], start.c[1], start.c[2]};
  if (fit({rgb.x, rgb.y, rgb.z}, c, maxIterations) > kFitTolerance) return std::nullopt;
  return RgbSigmoid{{float(c[0]), float(c[1]), float(c[2])}};
}

Vec3 reflectanceToLinearSrgb(const Spectrum& s) {
  const Observer& obs = Observer::cie1931();
  static const Spectrum d65 = *presetSpectrum("D65");
  double xyz[3] = {0.0, 0.0, 0.0}, norm = 0.0;
  for (int l = 360; l <= 830; ++l) {
    const double w = (l == 360 || l == 830) ? 0.5 : 1.0, e = double(d65(float(l))) * w;
    const double r = double(s(float(l)));
    xyz[0] += double(obs.xbar(float(l))) * e * r;
    xyz[1] += double(obs.ybar(float(l))) * e * r;
    xyz[2] += double(obs.zbar(float(l))) * e * r;
    norm += double(obs.ybar(float(l))) * e;
  }
  return xyzToLinearSrgb(Vec3(float(xyz[0] / norm), float(xyz[1] / norm), float(xyz[2] / norm)));
}

}  // namespace kasha
