#include "materials/measured_reradiation.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"
#include "materials/diffuse_lobe.h"

namespace kasha {
namespace {

const auto nm = formatNm;

void requireIncreasing(const std::vector<float>& g, const std::string& source, const char* what) {
  if (g.empty()) throw InputError(source, what, "no wavelengths");
  for (size_t k = 0; k < g.size(); ++k) {
    if (!(std::isfinite(g[k]) && g[k] > 0.0f)) throw InputError(source, what, "wavelength is not a positive number");
    if (k > 0 && !(g[k] > g[k - 1]))
      throw InputError(source, what, "wavelengths must be strictly increasing (" + nm(g[k - 1]) +
                                         " then " + nm(g[k]) + ")");
  }
}

}  // namespace

MeasuredMatrix::MeasuredMatrix(const BispectralData& data, MeasuredReradiationOptions options, WavelengthRange range)
    : in_(data.in), out_(data.out) {
  requireIncreasing(in_, data.source, "input wavelengths");
  requireIncreasing(out_, data.source, "output wavelengths");
  if (data.value.size() != in_.size() * out_.size())
    throw InputError(data.source, "", "matrix size does not match its wavelength grids");
  // Clean the noise and convert band values to densities per nm (header comment).
  f_.assign(data.value.size(), 0.0f);
  const std::vector<float> outWidth = bandWidths(out_);
  for (size_t i = 0; i < in_.size(); ++i)
    for (size_t o = 0; o < out_.size(); ++o) {
      const float v = data.at(o, i);
      if (!std::isfinite(v))
        throw InputError(data.source, "", "value at λ_i = " + nm(in_[i]) + ", λ_o = " + nm(out_[o]) + " nm is not finite");
      if (out_[o] == in_[i]) {
        diagL_.push_back(in_[i]);
        diagV_.push_back(std::max(v, 0.0f));
      } else if (out_[o] > in_[i] && v > options.noiseFloor) {
        f_[o * in_.size() + i] = v / outWidth[o];
      }
    }
  std::vector<float> line;
  for (size_t i = 0; i < in_.size(); ++i) {
    line.clear();
    for (size_t o = 0; o < out_.size(); ++o) line.push_back(f_[o * in_.size() + i]);
    const Spectrum s = Spectrum::piecewiseLinear(out_, line).zeroOutside();
    columns_.emplace_back(s, range);
  }
  for (size_t o = 0; o < out_.size(); ++o) {
    line.assign(f_.begin() + o * in_.size(), f_.begin() + (o + 1) * in_.size());
    const Spectrum s = Spectrum::piecewiseLinear(in_, line).zeroOutside();
    rows_.emplace_back(s, range);
  }
  for (size_t i = 0; i < in_.size(); ++i) {
    fluoresces_ = fluoresces_ || columns_[i].integral() > 0.0f;
    // Energy per input wavelength: d(λ_i) + ∫F dλ_o ≤ 1 (docs/transport.md §6: row sums of M ≤ 1).
    const float energy = diagonal(in_[i]) + columns_[i].integral();
    if (range.contains(in_[i]) && energy > 1.0f + kEnergyTolerance && !options.allowUnphysical)
      throw InputError(data.source, "ex_" + nm(in_[i]),
                       "reflects " + std::to_string(energy) + " of the light arriving at this wavelength, more than 1 + " +
                           std::to_string(kEnergyTolerance) + " (noise tolerance): the material would create energy "
                           "(set \"allow_unphysical\": true to render it anyway)");
  }
}

MeasuredMatrix::Bracket MeasuredMatrix::bracket(const std::vector<float>& g, float l) {
  Bracket b;
  if (!(l >= g.front() && l <= g.back())) return b;
  if (g.size() == 1) return {0, 0, 1.0f, 0.0f};
  const size_t k1 = std::clamp(size_t(std::upper_bound(g.begin(), g.end(), l) - g.begin()), size_t(1), g.size() - 1);
  const float t = (l - g[k1 - 1]) / (g[k1] - g[k1 - 1]);
  return {k1 - 1, k1, 1.0f - t, t};
}

float MeasuredMatrix::diagonal(float l) const {
  if (diagL_.empty()) return 0.0f;
  const Bracket b = bracket(diagL_, l);
  return b.w0 * diagV_[b.k0] + b.w1 * diagV_[b.k1];
}

float MeasuredMatrix::F(float lambdaOut, float lambdaIn) const {
  // Bilinear between the four surrounding knots (zero outside the measured grid).
  const Bracket bi = bracket(in_, lambdaIn), bo = bracket(out_, lambdaOut);
  const auto at = [&](size_t o, size_t i) { return f_[o * in_.size() + i]; };
  return bo.w0 * (bi.w0 * at(bo.k0, bi.k0) + bi.w1 * at(bo.k0, bi.k1)) +
         bo.w1 * (bi.w0 * at(bo.k1, bi.k0) + bi.w1 * at(bo.k1, bi.k1));
}

float MeasuredMatrix::A(float lambdaIn) const {
  const Bracket b = bracket(in_, lambdaIn);
  return b.w0 * columns_[b.k0].integral() + b.w1 * columns_[b.k1].integral();
}

float MeasuredMatrix::B(float lambdaOut) const {
  const Bracket b = bracket(out_, lambdaOut);
  return b.w0 * rows_[b.k0].integral() + b.w1 * rows_[b.k1].integral();
}

FluorophoreSpectra MeasuredMatrix::spectra() const {
  // A and B are linear between the knots (the lines' integrals) and zero outside the grid.
  std::vector<float> a, b;
  for (const SpectralDistribution& c : columns_) a.push_back(c.integral());
  for (const SpectralDistribution& r : rows_) b.push_back(r.integral());
  return FluorophoreSpectra{Spectrum::piecewiseLinear(in_, a).zeroOutside(), Spectrum::piecewiseLinear(out_, b).zeroOutside()};
}

WavelengthSample MeasuredMatrix::sampleLine(bool radiance, float lambdaKnown, float u) const {
  // Pick one of the two neighbouring lines in proportion to its weighted mass, then sample it.
  const std::vector<SpectralDistribution>& lines = radiance ? rows_ : columns_;
  const Bracket b = bracket(radiance ? out_ : in_, lambdaKnown);
  const float m0 = b.w0 * lines[b.k0].integral(), m1 = b.w1 * lines[b.k1].integral();
  float v = u * (m0 + m1);
  const bool first = v < m0 || !(m1 > 0.0f);
  v = first ? v / m0 : (v - m0) / m1;
  return lines[first ? b.k0 : b.k1].sample(std::min(v, 0x1.fffffep-1f));
}

float MeasuredMatrix::lineMass(bool radiance, float lambdaKnown, float lambdaOther) const {
  // The mixture of the two lines: F itself along the line (A or B times the density F/∫F).
  const std::vector<SpectralDistribution>& lines = radiance ? rows_ : columns_;
  const Bracket b = bracket(radiance ? out_ : in_, lambdaKnown);
  return b.w0 * lines[b.k0].integral() * lines[b.k0].pdf(lambdaOther) +
         b.w1 * lines[b.k1].integral() * lines[b.k1].pdf(lambdaOther);
}

float MeasuredModel::fluorescentWeight(TransportMode mode, float lambdaKnown) const {
  return mode == TransportMode::Importance ? A(lambdaKnown) : B(lambdaKnown);
}

float MeasuredModel::probFluorescence(TransportMode mode, float lambdaKnown) const {
  const float fl = fluorescentWeight(mode, lambdaKnown), el = diagonal(lambdaKnown);
  return fl + el > 0.0f ? fl / (fl + el) : 0.0f;
}

float MeasuredModel::eval(const ScatterQuery& query, const Vec3& wi, const Vec3& wo) const {
  if (!diffuse::sameSide(wi, wo)) return 0.0f;
  return (query.lobe == SpectralLobe::Elastic ? diagonal(query.lambdaIn) : F(query.lambdaOut, query.lambdaIn)) * kInvPi;
}

SpectralChoice MeasuredModel::sampleSpectral(TransportMode mode, float lambdaKnown, float u) const {
  const float fl = fluorescentWeight(mode, lambdaKnown), el = diagonal(lambdaKnown);
  if (!(fl + el > 0.0f)) return {};
  const float pFluor = fl / (fl + el);
  if (!(u < pFluor)) return {SpectralLobe::Elastic, lambdaKnown, 1.0f - pFluor};
  const WavelengthSample ws = m_->sampleLine(mode == TransportMode::Radiance, lambdaKnown, u / pFluor);
  if (ws.pdf <= 0.0f) return {};
  return {SpectralLobe::Fluorescent, ws.lambda, spectralPdf(mode, lambdaKnown, ws.lambda, SpectralLobe::Fluorescent)};
}

float MeasuredModel::spectralPdf(TransportMode mode, float lambdaKnown, float lambdaOther, SpectralLobe lobe) const {
  const float fl = fluorescentWeight(mode, lambdaKnown), el = diagonal(lambdaKnown);
  if (!(fl + el > 0.0f)) return 0.0f;
  if (lobe == SpectralLobe::Elastic) return el / (fl + el);
  // P(fluorescent)·F/∫F, where the mixture density of the two lines is exactly F/∫F.
  return reradiationScale_ * m_->lineMass(mode == TransportMode::Radiance, lambdaKnown, lambdaOther) / (fl + el);
}

}  // namespace kasha
