// RGB → reflectance spectrum (core/rgb_spectrum.h, Jakob & Hanika 2019): bounded in [0, 1],
// smooth, and reproducing the colour. The reproduction is checked by an independent forward
// model: the spectrum as tabulated per nm, integrated against the 1 nm CIE tables
// (reflectanceToLinearSrgb), not the fit's own 5 nm quadrature of the sigmoid.
#include <gtest/gtest.h>

#include <algorithm>
#include <iostream>
#include <random>

#include "core/error.h"
#include "core/rgb_spectrum.h"
#include "core/spectrum_json.h"

namespace kasha {
namespace {

float maxAbsDiff(const Vec3& a, const Vec3& b) {
  const Vec3 d = glm::abs(a - b);
  return std::max({d.x, d.y, d.z});
}

std::vector<Vec3> randomColours(int n, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  std::vector<Vec3> c(static_cast<size_t>(n));
  for (Vec3& v : c) v = Vec3(u(rng), u(rng), u(rng));
  return c;
}

// The table over the whole sRGB cube: every colour within 0.02 per component (the worst are near
// white, where the coefficients grow without bound), 0.0015 on average.
TEST(RgbSpectrum, TableReproducesColours) {
  double sum = 0.0;
  float worst = 0.0f;
  const std::vector<Vec3> colours = randomColours(1000, 7);
  for (const Vec3& c : colours) {
    const RgbSigmoid s = rgbToSigmoid(c);
    std::vector<float> x, y;
    for (int l = 360; l <= 830; ++l) {
      x.push_back(float(l));
      y.push_back(s(float(l)));
    }
    const float e = maxAbsDiff(reflectanceToLinearSrgb(Spectrum::piecewiseLinear(x, y)), c);
    EXPECT_LT(e, 0.02f) << c.x << " " << c.y << " " << c.z;
    worst = std::max(worst, e);
    sum += e;
  }
  EXPECT_LT(sum / double(colours.size()), 0.0015);
  std::cout << "table: mean error " << sum / double(colours.size()) << ", worst " << worst << "\n";
}

// A single colour is refined to the exact fit: within 5e-4, the difference between the fit's 5 nm
// quadrature and the check's 1 nm one for saturated greens.
TEST(RgbSpectrum, SingleColoursAreExact) {
  for (const Vec3& c : randomColours(200, 11)) {
    EXPECT_LT(maxAbsDiff(reflectanceToLinearSrgb(rgbToSpectrum(c, WavelengthRange{})), c), 5e-4f)
        << c.x << " " << c.y << " " << c.z;
  }
  // The primaries and secondaries of sRGB are reflectances too (JH19 fit all of sRGB).
  for (const Vec3& c : {Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1), Vec3(1, 1, 0), Vec3(0, 1, 1), Vec3(1, 0, 1)})
    EXPECT_LT(maxAbsDiff(reflectanceToLinearSrgb(rgbToSpectrum(c, WavelengthRange{})), c), 2e-3f)
        << c.x << " " << c.y << " " << c.z;
}

// Bounded in [0, 1] everywhere (also far outside the visible range), at most one extremum (the
// sigmoid of a quadratic), and smooth: the second difference per nm stays small.
TEST(RgbSpectrum, BoundedAndSmooth) {
  std::vector<Vec3> colours = randomColours(300, 3);
  colours.insert(colours.end(), {Vec3(0), Vec3(1), Vec3(1, 0, 0), Vec3(0, 0, 1), Vec3(0, 1, 0), Vec3(1, 1, 0.999f)});
  for (const Vec3& c : colours) {
    const RgbSigmoid s = rgbToSigmoid(c);
    int extrema = 0;
    float prev2 = s(200.0f), prev = s(201.0f), maxSecond = 0.0f;
    for (int l = 202; l <= 2500; ++l) {
      const float v = s(float(l));
      ASSERT_GE(v, 0.0f);
      ASSERT_LE(v, 1.0f);
      if ((prev - prev2) * (v - prev) < 0.0f && std::abs(v - prev) > 1e-6f) ++extrema;
      if (l <= 830) maxSecond = std::max(maxSecond, std::abs(v - 2.0f * prev + prev2));
      prev2 = prev;
      prev = v;
    }
    EXPECT_LE(extrema, 1) << c.x << " " << c.y << " " << c.z;
    // A step of 1 in 1 nm would be 1; the steepest sRGB colours change by a few % per nm.
    EXPECT_LT(maxSecond, 0.01f) << c.x << " " << c.y << " " << c.z;
  }
}

TEST(RgbSpectrum, GreysAreFlatAndEndsAreExact) {
  for (const float g : {0.02f, 0.18f, 0.5f, 0.9f}) {
    const Spectrum s = rgbToSpectrum(Vec3(g), WavelengthRange{});
    EXPECT_NEAR(s.minValue(360, 830), g, 2e-3f);
    EXPECT_NEAR(s.maxValue(360, 830), g, 2e-3f);
  }
  EXPECT_EQ(rgbToSigmoid(Vec3(0.0f))(550.0f), 0.0f);
  EXPECT_EQ(rgbToSigmoid(Vec3(std::nanf(""), 0.0f, 0.0f))(550.0f), 0.0f) << "non-finite is black";
  EXPECT_NEAR(rgbToSigmoid(Vec3(1.0f))(550.0f), 1.0f, 1e-4f);
  EXPECT_EQ(rgbToSigmoid(Vec3(2.0f, 0.5f, 0.25f)).c, rgbToSigmoid(Vec3(1.0f, 0.5f, 0.25f)).c) << "clamped to [0, 1]";
}

// The fit itself, from a cold start (all coefficients 0, the flat ½), converges for interior
// colours and its result reproduces them.
TEST(RgbSpectrum, GaussNewtonConvergesFromFlat) {
  for (const Vec3& c : randomColours(50, 5)) {
    const Vec3 inner = 0.05f + 0.9f * c;
    const std::optional<RgbSigmoid> s = fitRgbSigmoid(inner, RgbSigmoid{}, 200);
    ASSERT_TRUE(s) << inner.x << " " << inner.y << " " << inner.z;
    std::vector<float> x, y;
    for (int l = 360; l <= 830; ++l) {
      x.push_back(float(l));
      y.push_back((*s)(float(l)));
    }
    EXPECT_LT(maxAbsDiff(reflectanceToLinearSrgb(Spectrum::piecewiseLinear(x, y)), inner), 5e-4f);
  }
}

TEST(RgbSpectrum, SceneSpectrumType) {
  const SpectrumContext ctx{"scene.json", "."};
  const Spectrum s = parseSpectrum(nlohmann::json::parse(R"({"type": "rgb", "value": [0.2, 0.5, 0.1]})"), ctx, "/spectra/leaf");
  EXPECT_LT(maxAbsDiff(reflectanceToLinearSrgb(s), Vec3(0.2f, 0.5f, 0.1f)), 5e-4f);
  const auto error = [&](const char* text) -> std::string {
    try {
      parseSpectrum(nlohmann::json::parse(text), ctx, "/spectra/leaf");
    } catch (const InputError& e) {
      return e.what();
    }
    return "no error";
  };
  EXPECT_EQ(error(R"({"type": "rgb", "value": [0.2, 1.5, 0.1]})"),
            "scene.json: /spectra/leaf/value/1: reflectance colour component 1.500000 is outside [0, 1]");
  EXPECT_EQ(error(R"({"type": "rgb", "value": [0.2, 0.5]})"),
            "scene.json: /spectra/leaf/value: expected [r, g, b] (linear sRGB, each in [0, 1])");
  EXPECT_EQ(error(R"({"type": "rgb", "value": [0.2, "x", 0.1]})"),
            "scene.json: /spectra/leaf/value/1: expected a number, got string");
}

}  // namespace
}  // namespace kasha
