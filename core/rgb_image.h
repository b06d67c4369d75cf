#pragma once
// An RGB image that emits (environment maps, projectors, textured spots): linear sRGB texels, each upsampled to an
// emission spectrum (core/rgb_illuminant.h) and sampled in proportion to its luminance.
#include <cstdint>
#include <vector>

#include "core/color.h"
#include "core/math.h"
#include "core/rgb_illuminant.h"
#include "core/spectrum.h"

namespace kasha {

// Bytes a light casting or surrounding the scene with an image (envmap, projector, textured spot)
// holds per pixel while it is built: the decoded image, the texels' spectra, the sampling density.
constexpr uint64_t kEmittingImageBytesPerPixel = 64;

struct RgbImage {
  int width = 0, height = 0;
  std::vector<Vec3> pixels;  // linear RGB, row-major, row 0 at the top
};

// Each texel's emission spectrum, row-major.
std::vector<RgbIlluminant> upsampleTexels(const RgbImage& image);
// Each texel's luminance (negative values as 0), row-major.
std::vector<float> texelLuminances(const RgbImage& image);
// Σ w_i·L_i(λ) / total over the texels, tabulated every 5 nm over the range (a light's spectrum,
// which steers light selection).
Spectrum meanTexelSpectrum(const std::vector<RgbIlluminant>& texels, const std::vector<float>& weights, double total,
                           WavelengthRange range);

}  // namespace kasha
