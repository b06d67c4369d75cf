#include "core/spectral_film.h"

#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "core/bispectral_data.h"
#include "core/memory_budget.h"

namespace kasha {

int SpectralBins::index(float lambda) const {
  if (!(lambda >= min) || count < 1) return -1;
  const int i = int((lambda - min) / step);
  if (i < count) return i;
  return lambda <= min + float(count) * step ? count - 1 : -1;
}

SpectralBins SpectralBins::fromCount(const WavelengthRange& range, int count) {
  if (count < 1 || count > kMaxBins)
    throw std::invalid_argument("spectral bins: the count must be in 1.." + std::to_string(kMaxBins) + ", got " +
                                std::to_string(count));
  return {range.min, range.width() / float(count), count};
}

SpectralBins SpectralBins::fromStep(const WavelengthRange& range, double step) {
  if (!(step > 0.0) || !std::isfinite(step))
    throw std::invalid_argument("spectral step: must be a positive number of nm");
  const std::string where = " the scene's wavelength range (" + formatNm(range.min) + "-" + formatNm(range.max) + " nm)";
  const double n = double(range.width()) / step;
  if (n > double(kMaxBins) + 0.5) {
    char text[32];
    std::snprintf(text, sizeof text, "%g", step);
    throw std::invalid_argument("spectral step: " + std::string(text) + " nm makes more than " + std::to_string(kMaxBins) +
                                " bins of" + where);
  }
  const double rounded = std::round(n);
  if (rounded < 1.0 || std::abs(n - rounded) * step > 1e-3)
    throw std::invalid_argument("spectral step: " + formatNm(float(step)) + " nm does not divide" + where);
  return fromCount(range, int(rounded));
}

uint64_t SpectralFilm::bytesFor(int width, int height, int bins) {
  return saturatingMul(saturatingMul(uint64_t(width) * uint64_t(height), uint64_t(bins)), sizeof(double));
}

void SpectralFilm::add(int x, int y, float lambda, float value) {
  const int b = bins_.index(lambda);
  if (b < 0 || !std::isfinite(value)) return;
  sum_[(size_t(y) * w_ + x) * size_t(bins_.count) + size_t(b)] += double(value);
}

float SpectralFilm::value(int x, int y, int b) const {
  if (spp_ == 0) return 0.0f;
  return float(sum_[(size_t(y) * w_ + x) * size_t(bins_.count) + size_t(b)] / (double(spp_) * double(bins_.step)));
}

void SpectralFilm::restore(std::vector<double> sums, int spp) {
  if (sums.size() != sum_.size()) throw std::invalid_argument("SpectralFilm::restore: buffer size does not match the film");
  sum_ = std::move(sums);
  spp_ = spp;
}

}  // namespace kasha
