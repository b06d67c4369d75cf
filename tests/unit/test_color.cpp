// Colorimetry (core/color.h): the CIE 1931 observer tables, the film's XYZ normalisation checked
// against the published chromaticities of the standard illuminants, XYZ → sRGB, and the camera's
// wavelength densities (scene/wavelength_strategy.h, site Sensor).
#include <gtest/gtest.h>

#include <cmath>
#include <functional>

#include "core/color.h"
#include "core/spectrum_presets.h"
#include "scene/wavelength_strategy.h"

namespace kasha {
namespace {

// ∫ f over [lo, hi] by Simpson's rule on `step`-nm panels: exact for the product of two
// piecewise-linear functions with knots on the grid (the CIE tables are at 1 nm). Ends are
// evaluated just inside, so a step at lo or hi counts from the inside.
double integrate(const std::function<double(float)>& f, float lo, float hi, float step = 0.5f) {
  const int n = int(std::lround((hi - lo) / step));
  const double h = double(hi - lo) / n, eps = 1e-4;
  double sum = 0.0;
  for (int i = 0; i < n; ++i) {
    const double a = lo + i * h, b = a + h;
    const double fa = f(float(i == 0 ? a + eps : a)), fb = f(float(i == n - 1 ? b - eps : b));
    sum += h / 6.0 * (fa + 4.0 * f(float(0.5 * (a + b))) + fb);
  }
  return sum;
}

// XYZ of a radiance spectrum as the film computes it: ∫ weight(λ)·L(λ) dλ over 360–830 nm,
// weight = (x̄, ȳ, z̄) / ∫ȳ.
Vec3 filmXyz(const Spectrum& L) {
  const Observer& o = Observer::cie1931();
  Vec3 xyz;
  for (int c = 0; c < 3; ++c)
    xyz[c] = float(integrate([&](float l) { return double(o.weight(l)[c]) * L(l); }, 360.0f, 830.0f));
  return xyz;
}

Vec2 chromaticity(const Vec3& xyz) {
  const float s = xyz.x + xyz.y + xyz.z;
  return {xyz.x / s, xyz.y / s};
}

TEST(Cie1931, ColourMatchingIntegrals) {
  const Observer& o = Observer::cie1931();
  EXPECT_NEAR(o.yIntegral, 106.857, 1e-3 * 106.857);
  EXPECT_FLOAT_EQ(o.ybar.integral(360.0f, 830.0f), o.yIntegral);
  const double x = o.xbar.integral(360.0f, 830.0f), y = o.ybar.integral(360.0f, 830.0f),
               z = o.zbar.integral(360.0f, 830.0f);
  EXPECT_NEAR(x / y, 1.0, 0.01);
  EXPECT_NEAR(z / y, 1.0, 0.01);
  // The tables agree with the exact product integral used below.
  EXPECT_NEAR(integrate([&](float l) { return o.ybar(l); }, 360.0f, 830.0f), y, 1e-4 * y);
  // A few tabulated values, and zero outside the table.
  EXPECT_NEAR(o.ybar(555.0f), 1.0f, 1e-3f);
  EXPECT_NEAR(o.xbar(600.0f), 1.0622f, 1e-3f);
  EXPECT_NEAR(o.zbar(450.0f), 1.7721f, 1e-3f);
  for (float l : {300.0f, 359.0f, 831.0f, 900.0f}) {
    EXPECT_EQ(o.xbar(l), 0.0f) << l;
    EXPECT_EQ(o.ybar(l), 0.0f) << l;
    EXPECT_EQ(o.zbar(l), 0.0f) << l;
  }
}

TEST(Cie1931, WeightIsTheThreeTablesLookedUpOneByOne) {
  // weight() finds the segment once for the three tables; it must give each table's own lookup,
  // bit for bit, on and between the knots, at the ends and outside the tables.
  const Observer& o = Observer::cie1931();
  ASSERT_TRUE(o.sharedKnots);
  for (float lambda = 340.0f; lambda <= 850.0f; lambda += 0.0371f) {
    const Vec3 each = Vec3(o.xbar(lambda), o.ybar(lambda), o.zbar(lambda)) / o.yIntegral;
    ASSERT_EQ(o.weight(lambda), each) << "λ = " << lambda;
  }
  for (const float lambda : {360.0f, 360.5f, 361.0f, 829.5f, 830.0f, 555.0f})
    EXPECT_EQ(o.weight(lambda), Vec3(o.xbar(lambda), o.ybar(lambda), o.zbar(lambda)) / o.yIntegral) << lambda;
}

TEST(Cie1931, D65ChromaticityAndWhiteInSrgb) {
  const auto d65 = presetSpectrum("D65");
  ASSERT_TRUE(d65);
  const Vec3 xyz = filmXyz(*d65);
  const Vec2 xy = chromaticity(xyz);
  EXPECT_NEAR(xy.x, 0.31273f, 2e-4f);
  EXPECT_NEAR(xy.y, 0.32902f, 2e-4f);
  // D65 is the white of sRGB: equal linear R, G, B.
  const Vec3 rgb = xyzToLinearSrgb(xyz);
  EXPECT_GT(rgb.g, 0.0f);
  EXPECT_NEAR(rgb.r / rgb.g, 1.0f, 1e-3f);
  EXPECT_NEAR(rgb.b / rgb.g, 1.0f, 1e-3f);
  // sRGB's reference white XYZ (Y = 1) maps to (1, 1, 1).
  const Vec3 white = xyzToLinearSrgb(Vec3(0.95047f, 1.0f, 1.08883f));
  EXPECT_NEAR(white.r, 1.0f, 1e-3f);
  EXPECT_NEAR(white.g, 1.0f, 1e-3f);
  EXPECT_NEAR(white.b, 1.0f, 1e-3f);
}

TEST(Cie1931, IlluminantAChromaticity) {
  const auto a = presetSpectrum("A");
  ASSERT_TRUE(a);
  const Vec2 xy = chromaticity(filmXyz(*a));
  EXPECT_NEAR(xy.x, 0.44757f, 2e-4f);
  EXPECT_NEAR(xy.y, 0.40744f, 2e-4f);
}

TEST(Cie1931, EqualEnergyHasUnitY) {
  const auto e = presetSpectrum("E");
  ASSERT_TRUE(e);
  const Vec3 xyz = filmXyz(*e);
  EXPECT_NEAR(xyz.y, 1.0f, 1e-4f);
  const Vec2 xy = chromaticity(xyz);
  EXPECT_NEAR(xy.x, 1.0f / 3.0f, 2e-4f);
  EXPECT_NEAR(xy.y, 1.0f / 3.0f, 2e-4f);
  // Linear in the radiance.
  EXPECT_NEAR(filmXyz(e->scaled(2.5f)).y, 2.5f, 2.5e-4f);
}

TEST(Cie1931, PresetsExist) {
  for (const std::string& name : presetNames()) {
    const auto s = presetSpectrum(name);
    ASSERT_TRUE(s) << name;
    EXPECT_GT(s->integral(380.0f, 780.0f), 0.0f) << name;
  }
  EXPECT_FALSE(presetSpectrum("D50"));
  EXPECT_FALSE(presetSpectrum("F13"));
  // D65 and A are relative SPDs, 100 at 560 nm.
  EXPECT_NEAR((*presetSpectrum("D65"))(560.0f), 100.0f, 0.5f);
  EXPECT_NEAR((*presetSpectrum("A"))(560.0f), 100.0f, 0.5f);
}

TEST(Srgb, EncodeEndpoints) {
  EXPECT_EQ(srgbEncode(0.0f), 0.0f);
  EXPECT_NEAR(srgbEncode(1.0f), 1.0f, 1e-6f);
  EXPECT_EQ(srgbEncode(-0.5f), 0.0f);  // clamped
  EXPECT_NEAR(srgbEncode(7.0f), 1.0f, 1e-6f);
  // The linear toe and the knee where the two pieces meet (continuous there).
  EXPECT_NEAR(srgbEncode(0.001f), 0.01292f, 1e-6f);
  EXPECT_NEAR(srgbEncode(0.0031308f), 0.04045f, 1e-4f);
  EXPECT_NEAR(srgbEncode(0.0031309f), srgbEncode(0.0031308f), 1e-5f);
  EXPECT_NEAR(srgbEncode(0.18f), 0.4614f, 1e-3f);  // middle grey
  float prev = -1.0f;
  for (float v = 0.0f; v <= 1.0f; v += 1.0f / 64.0f) {
    EXPECT_GT(srgbEncode(v), prev) << v;
    prev = srgbEncode(v);
  }
}

// The sensor's density for strategy `name` in an empty scene with the given wavelength range.
WavelengthDensity sensorDensity(const std::string& name, WavelengthRange range) {
  Scene scene;
  scene.range = range;
  return WavelengthStrategy(parseWavelengthSpec(name), WavelengthSources(scene), WavelengthSite::Sensor).density();
}

// ∫ pdf over [lo, hi] by the trapezoid rule on a fine grid.
double pdfIntegral(const WavelengthDensity& s, float lo, float hi) {
  const int n = int((hi - lo) * 8.0f);
  double sum = 0.0;
  for (int i = 0; i < n; ++i) {
    const float a = lo + (hi - lo) * float(i) / float(n), b = lo + (hi - lo) * float(i + 1) / float(n);
    sum += 0.5 * double(s.pdf(a) + s.pdf(b)) * double(b - a);
  }
  return sum;
}

TEST(SensorSampling, DensitiesIntegrateToOneOverTheVisibleRange) {
  for (const std::string mode : {"uniform", "cmf"}) {
    for (WavelengthRange range : {WavelengthRange{360.0f, 830.0f}, WavelengthRange{300.0f, 830.0f},
                                  WavelengthRange{300.0f, 1000.0f}}) {
      SCOPED_TRACE(mode + " " + std::to_string(range.min) + "-" + std::to_string(range.max));
      const WavelengthDensity s = sensorDensity(mode, range);
      EXPECT_NEAR(pdfIntegral(s, 360.0f, 830.0f), 1.0, 2e-3);
      for (float l : {250.0f, 300.0f, 340.0f, 359.5f, 830.5f, 900.0f}) EXPECT_EQ(s.pdf(l), 0.0f) << l;
      for (int i = 0; i < 256; ++i) {
        const WavelengthSample w = s.sample((float(i) + 0.5f) / 256.0f);
        EXPECT_GE(w.lambda, 360.0f);
        EXPECT_LE(w.lambda, 830.0f);
        EXPECT_GT(w.pdf, 0.0f);
        EXPECT_FLOAT_EQ(w.pdf, s.pdf(w.lambda));
      }
    }
  }
  // A scene range inside the visible: the density covers only it.
  const WavelengthDensity narrow = sensorDensity("uniform", {400.0f, 700.0f});
  EXPECT_NEAR(narrow.pdf(550.0f), 1.0f / 300.0f, 1e-6f);
  EXPECT_EQ(narrow.pdf(380.0f), 0.0f);
  EXPECT_NEAR(pdfIntegral(narrow, 360.0f, 830.0f), 1.0, 1e-3);
  EXPECT_NEAR(pdfIntegral(sensorDensity("cmf", {400.0f, 700.0f}), 360.0f, 830.0f), 1.0, 2e-3);
}

TEST(SensorSampling, ShapeOfTheDensities) {
  const WavelengthDensity u = sensorDensity("uniform", {300.0f, 830.0f});
  EXPECT_NEAR(u.pdf(400.0f), 1.0f / 470.0f, 1e-7f);
  EXPECT_NEAR(u.pdf(800.0f), 1.0f / 470.0f, 1e-7f);
  const WavelengthDensity c = sensorDensity("cmf", {300.0f, 830.0f});
  const Observer& o = Observer::cie1931();
  auto sum = [&](float l) { return o.xbar(l) + o.ybar(l) + o.zbar(l); };
  EXPECT_NEAR(c.pdf(550.0f) / c.pdf(450.0f), sum(550.0f) / sum(450.0f), 1e-3f);
  EXPECT_NEAR(c.pdf(600.0f) / c.pdf(500.0f), sum(600.0f) / sum(500.0f), 1e-3f);
}

}  // namespace
}  // namespace kasha
