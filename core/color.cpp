#include "core/color.h"

#include <algorithm>
#include <cmath>

#include "core/embedded_data.h"
#include "core/spectrum_csv.h"

namespace kasha {

const Observer& Observer::cie1931() {
  static const Observer obs = [] {
    const SpectralTable t = parseSpectralCsv(embeddedFile("cie1931_2deg_cmf_1nm.csv"), "cie1931_2deg_cmf_1nm.csv");
    Observer o{spectrumFromTable(t, "xbar").zeroOutside(), spectrumFromTable(t, "ybar").zeroOutside(),
               spectrumFromTable(t, "zbar").zeroOutside(), 0.0f};
    o.yIntegral = o.ybar.integral(360.0f, 830.0f);
    o.sharedKnots = o.xbar.lambdas() == o.ybar.lambdas() && o.zbar.lambdas() == o.ybar.lambdas();
    return o;
  }();
  return obs;
}

Vec3 Observer::xyz(const Spectrum& L, WavelengthRange range) const {
  std::vector<float> knots{range.min, range.max};
  for (const Spectrum* s : {&xbar, &ybar, &zbar, &L})
    for (const float x : s->lambdas())
      if (x > range.min && x < range.max) knots.push_back(x);
  std::sort(knots.begin(), knots.end());
  knots.erase(std::unique(knots.begin(), knots.end()), knots.end());
  // Each piece's ends are read on its own side of a step (right limit at a, left limit at b).
  const auto at = [&](float l, bool left) {
    const Vec3 w = left ? Vec3(xbar.leftLimit(l), ybar.leftLimit(l), zbar.leftLimit(l)) : Vec3(xbar(l), ybar(l), zbar(l));
    return glm::dvec3(w) * double(left ? L.leftLimit(l) : L(l));
  };
  glm::dvec3 sum(0.0);
  for (size_t i = 0; i + 1 < knots.size(); ++i) {
    const float a = knots[i], b = knots[i + 1];
    sum += (double(b) - double(a)) / 6.0 * (at(a, false) + 4.0 * at(0.5f * (a + b), false) + at(b, true));
  }
  return Vec3(sum / double(yIntegral));
}

Vec3 xyzToLinearSrgb(const Vec3& c) {
  return Vec3(3.2404542f * c.x - 1.5371385f * c.y - 0.4985314f * c.z,
              -0.9692660f * c.x + 1.8760108f * c.y + 0.0415560f * c.z,
              0.0556434f * c.x - 0.2040259f * c.y + 1.0572252f * c.z);
}

float srgbEncode(float v) {
  v = std::clamp(v, 0.0f, 1.0f);
  return v <= 0.0031308f ? 12.92f * v : 1.055f * std::pow(v, 1.0f / 2.4f) - 0.055f;
}

float srgbDecode(float v) {
  v = std::clamp(v, 0.0f, 1.0f);
  return v <= 0.04045f ? v / 12.92f : std::pow((v + 0.055f) / 1.055f, 2.4f);
}

}  // namespace kasha
