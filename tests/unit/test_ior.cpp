// Unit tests of the index of refraction models (materials/ior.h) against published values and
// values computed by hand from the formulas.
#include <gtest/gtest.h>

#include <cmath>

#include "materials/ior.h"

namespace kasha {
namespace {

// Fraunhofer lines (nm): d (helium), F and C (hydrogen), where glass catalogues quote n.
constexpr float kD = 587.5618f, kF = 486.1327f, kC = 656.2725f;

double abbeNumber(const Ior& n) { return (n(kD) - 1.0) / (n(kF) - n(kC)); }

TEST(Ior, Bk7MatchesSchottDataSheet) {
  // Schott N-BK7 data sheet: n_d = 1.51680, n_F = 1.52238, n_C = 1.51432, ν_d = 64.17.
  const Ior n = *Ior::preset("BK7");
  EXPECT_NEAR(n(kD), 1.5168, 1e-4);
  EXPECT_NEAR(n(kF), 1.52238, 1e-4);
  EXPECT_NEAR(n(kC), 1.51432, 1e-4);
  EXPECT_NEAR(abbeNumber(n), 64.17, 0.05);
  EXPECT_TRUE(n.dispersive());
}

TEST(Ior, FusedSilicaMatchesMalitson) {
  // Malitson 1965, table and abstract: n_d = 1.4585, n_F = 1.4631, n_C = 1.4564, ν_d = 67.8.
  const Ior n = *Ior::preset("fused_silica");
  EXPECT_NEAR(n(kD), 1.4585, 1e-4);
  EXPECT_NEAR(n(kF), 1.4631, 1e-4);
  EXPECT_NEAR(n(kC), 1.4564, 1e-4);
  EXPECT_NEAR(abbeNumber(n), 67.8, 0.05);
}

TEST(Ior, NormalDispersionOverTheVisible) {
  // Both glasses have their resonances in the UV and IR: n falls strictly with λ in between.
  for (const std::string& name : Ior::presetNames()) {
    const Ior n = *Ior::preset(name);
    for (float l = 361.0f; l <= 830.0f; l += 1.0f) EXPECT_LT(n(l), n(l - 1.0f)) << name << " at " << l << " nm";
  }
}

TEST(Ior, CauchyByHand) {
  // n = A + B/λ² + C/λ⁴ with λ in µm: at 500 nm, λ² = 0.25 µm², λ⁴ = 0.0625 µm⁴.
  const Ior n = Ior::cauchy(1.5, 0.004, 1e-4);
  EXPECT_NEAR(n(500.0f), 1.5 + 0.004 / 0.25 + 1e-4 / 0.0625, 1e-6);
  EXPECT_NEAR(n(1000.0f), 1.5 + 0.004 + 1e-4, 1e-6);
  EXPECT_TRUE(n.dispersive());
  EXPECT_FALSE(Ior::cauchy(1.5, 0.0, 0.0).dispersive());
  // The textbook two-term fit of BK7 (A = 1.5046, B = 0.00420 µm²) follows the Sellmeier
  // formula to about 1e-4 across 400–700 nm.
  const Ior fit = Ior::cauchy(1.5046, 0.00420, 0.0), bk7 = *Ior::preset("BK7");
  for (float l = 400.0f; l <= 700.0f; l += 10.0f) EXPECT_NEAR(fit(l), bk7(l), 1.5e-4) << l << " nm";
}

TEST(Ior, SellmeierByHand) {
  // One term: n² = 1 + B·λ²/(λ² − C); at 1000 nm with B = 1, C = 0.5 µm²: n² = 1 + 1/0.5 = 3.
  const Ior n = Ior::sellmeier({1.0, 0.0, 0.0}, {0.5, 0.0, 0.0});
  EXPECT_NEAR(n(1000.0f), std::sqrt(3.0), 1e-6);
  // No coefficients: vacuum.
  EXPECT_EQ(Ior::sellmeier({0.0, 0.0, 0.0}, {0.0, 0.0, 0.0})(550.0f), 1.0f);
  EXPECT_FALSE(Ior::sellmeier({0.0, 0.0, 0.0}, {1.0, 2.0, 3.0}).dispersive());
}

TEST(Ior, ConstantIsFlat) {
  const Ior n = Ior::constant(1.33);
  EXPECT_FLOAT_EQ(n(400.0f), 1.33f);
  EXPECT_FLOAT_EQ(n(800.0f), 1.33f);
  EXPECT_FALSE(n.dispersive());
}

TEST(Ior, UnknownPreset) {
  EXPECT_FALSE(Ior::preset("bk7"));  // names are case-sensitive
  EXPECT_FALSE(Ior::preset("diamond"));
}

TEST(Ior, CheckRejectsNonPhysicalIndices) {
  const WavelengthRange range{360.0f, 830.0f};
  EXPECT_EQ(checkIor(*Ior::preset("BK7"), range), "");
  EXPECT_EQ(checkIor(*Ior::preset("fused_silica"), WavelengthRange{200.0f, 2500.0f}), "");
  EXPECT_EQ(checkIor(Ior::constant(1.0), range), "");
  EXPECT_NE(checkIor(Ior::constant(0.9), range).find("below 1"), std::string::npos);
  EXPECT_NE(checkIor(Ior::constant(std::nan("")), range).find("not a finite"), std::string::npos);
  // A Cauchy form that falls below 1 only at the long end of the range.
  // 0.9 + 0.05/λ² drops below 1 beyond √0.5 µm ≈ 707 nm.
  const std::string cauchy = checkIor(Ior::cauchy(0.9, 0.05, 0.0), range);
  EXPECT_NE(cauchy.find("below 1"), std::string::npos) << cauchy;
  EXPECT_EQ(checkIor(Ior::cauchy(0.9, 0.05, 0.0), WavelengthRange{360.0f, 700.0f}), "");
  // A Sellmeier pole at 500 nm (C = 0.25 µm²) inside the range, and n² < 0 just above it.
  const std::string pole = checkIor(Ior::sellmeier({1.0, 0.0, 0.0}, {0.25, 0.0, 0.0}), range);
  EXPECT_NE(pole.find("pole at 500"), std::string::npos) << pole;
  const std::string negative =
      checkIor(Ior::sellmeier({-3.0, 0.0, 0.0}, {0.01, 0.0, 0.0}), WavelengthRange{360.0f, 830.0f});
  EXPECT_NE(negative.find("not a finite"), std::string::npos) << negative;
}

}  // namespace
}  // namespace kasha
