#pragma once
// Spectral bins of a render: per pixel, the spectral radiance per nm averaged over each of N equal
// wavelength bins of the scene's range, as the emissive layout of Fichet et al. (2021) stores it
// (core/spectral_exr.h). Estimator: a sample at λ carrying L(λ)/p(λ) (the quantity the XYZ film
// weights by W(λ), core/color.h) adds L/(p·Δ) to the bin holding λ; divided by the samples per
// pixel its mean is (1/Δ)∫_bin L dλ. Bins where the sensor's wavelength density is zero stay zero.
#include <cstdint>
#include <string>
#include <vector>

#include "core/spectrum.h"

namespace kasha {

// N equal bins [min + iΔ, min + (i+1)Δ).
struct SpectralBins {
  float min = 0.0f, step = 0.0f;
  int count = 0;

  bool enabled() const { return count > 0; }
  float centre(int i) const { return min + (float(i) + 0.5f) * step; }
  float lower(int i) const { return min + float(i) * step; }
  // The bin holding λ, or -1 outside [min, min + count·step] (the upper end belongs to the last bin).
  int index(float lambda) const;

  // `count` bins over `range`. Throws std::invalid_argument if count < 1 or over kMaxBins.
  static SpectralBins fromCount(const WavelengthRange& range, int count);
  // Bins `step` nm wide over `range`; the step must make at most kMaxBins bins and divide the
  // range's width (within 1e-3 nm) so that no bin reaches past it. Throws std::invalid_argument
  // with the reason. A double, so that a tiny step is refused rather than rounded to 0.
  static SpectralBins fromStep(const WavelengthRange& range, double step);
  static constexpr int kMaxBins = 4096;
};

class SpectralFilm {
 public:
  SpectralFilm(int width, int height, SpectralBins bins)
      : w_(width), h_(height), bins_(bins), sum_(size_t(width) * height * size_t(bins.count)) {}

  // Bytes a film of this size allocates (one double per pixel and bin), to check a memory limit first.
  static uint64_t bytesFor(int width, int height, int bins);

  // Adds a sample's L/p at λ (not thread-safe per pixel; the render loop adds a pixel's camera
  // samples from one task and splats after each pass). Non-finite values and λ outside the bins
  // are dropped: the XYZ film counts the non-finite ones.
  void add(int x, int y, float lambda, float value);
  void setSamplesPerPixel(int spp) { spp_ = spp; }
  int samplesPerPixel() const { return spp_; }
  int width() const { return w_; }
  int height() const { return h_; }
  const SpectralBins& bins() const { return bins_; }
  // Radiance per nm of bin b at the pixel: sum / (spp·Δ).
  float value(int x, int y, int b) const;

  // The raw sums, pixel-major then bin (for checkpoints), and their restoration.
  const std::vector<double>& sums() const { return sum_; }
  void restore(std::vector<double> sums, int spp);

 private:
  int w_, h_, spp_ = 0;
  SpectralBins bins_;
  std::vector<double> sum_;
};

}  // namespace kasha
