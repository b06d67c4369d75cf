// The opacity mask's per-hit model (materials/opacity_mask.h) at one point: samples agree with
// the densities pdf() reports, forward and reverse; the pass-through is drawn with probability
// 1 − α, continues straight on and carries the path weight 1; and α = 0 passes everything.
#include <gtest/gtest.h>

#include <cmath>

#include "core/rng.h"
#include "materials/material_json.h"
#include "materials/opacity_mask.h"
#include "tests/material_support.h"

namespace kasha {
namespace {

std::unique_ptr<Material> masked(float opacity, const std::string& nested) {
  const nlohmann::json v = nlohmann::json::parse(R"({"type": "mask", "opacity": )" + std::to_string(opacity) +
                                                 R"(, "material": )" + nested + "}");
  return parseMaterial(v, SpectrumContext("test.json", "."), "/materials/m", WavelengthRange{});
}

const std::string kJung = R"({"type": "jung_fluorescent", "absorption": {"type": "gaussian", "center": 450, "fwhm": 80,
  "peak": 0.9}, "emission": {"type": "gaussian", "center": 540, "fwhm": 40}, "reflectance": 0.7, "c": 0.6, "Q": 0.8})";
const std::string kMetal = R"({"type": "rough_conductor", "reflectance": 0.8, "alpha": 0.3})";

TEST(MaskModel, SamplesMatchTheirDensitiesAndPassThroughOneMinusAlpha) {
  const float alpha = 0.4f;
  for (const std::string& nested : {kJung, kMetal}) {
    const auto m = masked(alpha, nested);
    const Bsdf b = test::localBsdf(*m, 480.0f);
    Rng rng(11);
    for (const TransportMode mode : {TransportMode::Radiance, TransportMode::Importance}) {
      const int n = 20000;
      int through = 0, checked = 0;
      for (int i = 0; i < n; ++i) {
        const Vec3 known = test::dirFromCosPhi(0.2f + 0.7f * rng.uniform(), 6.28f * rng.uniform());
        const std::optional<ScatterSample> s = b.sample(mode, known, 480.0f, Vec3(rng.uniform(), rng.uniform(), rng.uniform()));
        if (!s) continue;
        const bool radiance = mode == TransportMode::Radiance;
        const Vec3 wi = radiance ? s->w : known, wo = radiance ? known : s->w;
        const float li = radiance ? s->lambda : 480.0f, lo = radiance ? 480.0f : s->lambda;
        const ScatterDensity d = b.pdf({mode, s->lobe, li, lo}, wi, wo);
        EXPECT_TRUE(test::close(s->pdf, d.pdf, 1e-4)) << nested;
        EXPECT_TRUE(test::close(s->pdfRev, d.pdfRev, 1e-4)) << nested;
        ++checked;
        if (s->specular) {
          ++through;
          EXPECT_EQ(s->w, -known);
          EXPECT_EQ(s->lobe, SpectralLobe::Elastic);
          EXPECT_NEAR(s->f * std::abs(s->w.z) / s->pdf, 1.0f, 1e-5f) << "the pass-through's path weight";
        }
      }
      EXPECT_GT(checked, n / 2);
      const double p = 1.0 - alpha, se = std::sqrt(p * (1.0 - p) / n);
      EXPECT_NEAR(double(through) / n, p, 4.0 * se) << nested << " " << toString(mode);
    }
  }
}

TEST(MaskModel, TransparentMaskPassesEverything) {
  const auto m = masked(0.0f, kJung);
  const Bsdf b = test::localBsdf(*m, 480.0f);
  const Vec3 known = test::dirFromCosPhi(0.6f, 1.0f);
  for (const float u : {0.0f, 0.3f, 0.99f}) {
    const std::optional<ScatterSample> s = b.sample(TransportMode::Radiance, known, 480.0f, Vec3(u, u, u));
    ASSERT_TRUE(s);
    EXPECT_TRUE(s->specular);
    EXPECT_EQ(s->w, -known);
  }
  EXPECT_EQ(
      b.eval({TransportMode::Radiance, SpectralLobe::Elastic, 480.0f, 480.0f}, test::dirFromCosPhi(0.5f, 0.0f), known),
      0.0f);
  EXPECT_EQ(b.fluorescenceProbability(TransportMode::Radiance, 480.0f), 0.0f);
}

}  // namespace
}  // namespace kasha
