#include "core/rgb_image.h"

#include <algorithm>

namespace kasha {

std::vector<RgbIlluminant> upsampleTexels(const RgbImage& image) {
  std::vector<RgbIlluminant> t;
  t.reserve(image.pixels.size());
  for (const Vec3& p : image.pixels) t.push_back(rgbIlluminant(p));
  return t;
}

std::vector<float> texelLuminances(const RgbImage& image) {
  std::vector<float> w;
  w.reserve(image.pixels.size());
  for (const Vec3& p : image.pixels) w.push_back(std::max(0.0f, luminance(p)));
  return w;
}

Spectrum meanTexelSpectrum(const std::vector<RgbIlluminant>& texels, const std::vector<float>& weights, double total,
                           WavelengthRange range) {
  std::vector<float> wl, v;
  for (float nm = range.min;; nm = std::min(nm + 5.0f, range.max)) {
    double sum = 0.0;
    for (size_t i = 0; i < texels.size(); ++i) sum += double(texels[i](nm)) * double(weights[i]);
    wl.push_back(nm);
    v.push_back(float(sum / total));
    if (nm >= range.max) break;
  }
  return Spectrum::piecewiseLinear(std::move(wl), std::move(v));
}

}  // namespace kasha
