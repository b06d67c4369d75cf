// Zhdanov's three-part fluorescent BDF (materials/zhdanov_bdf.h): χ² sampling in both transport
// modes, sample()/pdf() consistency, energy (eqs. 2–4 with the modified Phong gloss peak),
// directional reciprocity, the white furnace of light paths, and parameter checks. Expected values
// come from the formulas in the header or from quadrature of the material's own eval()/pdf().
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <tuple>
#include <vector>

#include "materials/zhdanov_bdf.h"
#include "tests/material_chi2.h"
#include "tests/material_support.h"

namespace kasha {
namespace {

using test::close;
using test::Event;
using test::physical;

const WavelengthRange kRange{360.0f, 830.0f};

// Gloss, a sloped passive part and factorised fluorescence with A on 380–480 nm and E about 560 nm.
ZhdanovParams glossyParams() {
  ZhdanovParams p;
  p.gloss = 0.15f;
  p.glossExponent = 6.0f;
  p.passive = Spectrum::piecewiseLinear({360.0f, 830.0f}, {0.2f, 0.6f});
  p.excitation = Spectrum::piecewiseLinear({380.0f, 430.0f, 480.0f}, {0.0f, 0.5f, 0.0f}).zeroOutside();
  p.emission = Spectrum::gaussian(560.0f, 60.0f, 3.0f);
  return p;
}

// No gloss and p + A = 1 everywhere: every unit of light arriving is reflected (white furnace).
ZhdanovParams furnaceParams() {
  ZhdanovParams p = glossyParams();
  p.gloss = 0.0f;
  const Spectrum one = Spectrum::constant(1.0f);
  p.passive = Spectrum::weightedSum({{1.0f, &one}, {-1.0f, &p.excitation}});
  return p;
}

// Only the gloss peak, no colour, no fluorescence.
ZhdanovParams glossOnlyParams() {
  ZhdanovParams p;
  p.gloss = 0.8f;
  p.glossExponent = 10.0f;
  p.passive = Spectrum::constant(0.0f);
  p.excitation = Spectrum::constant(0.0f);
  p.emission = Spectrum::constant(1.0f);
  return p;
}

std::vector<std::pair<const char*, ZhdanovParams>> allParams() {
  return {{"glossy", glossyParams()}, {"furnace", furnaceParams()}, {"gloss_only", glossOnlyParams()}};
}

TEST(ZhdanovChi2, BothModesJointDirectionWavelengthSlow) {
  uint64_t seed = 1;
  // The gloss peak varies within a direction cell: finer quadrature where it dominates.
  const std::vector<std::tuple<const char*, ZhdanovParams, int>> cases = {{"glossy", glossyParams(), 8},
                                                                          {"gloss_only", glossOnlyParams(), 20}};
  for (const auto& [name, params, subDir] : cases) {
    const ZhdanovBdf m(params, kRange);
    for (const TransportMode mode : {TransportMode::Radiance, TransportMode::Importance})
      for (const float l : {420.0f, 560.0f})
        for (const Vec3 wk : {Vec3(0.3f, -0.2f, 0.8f), Vec3(0.7f, 0.1f, -0.3f)}) {
          SCOPED_TRACE(std::string(name) + " " + toString(mode) + " λ = " + std::to_string(l) + " ω.z = " +
                       std::to_string(wk.z));
          test::Chi2Config cfg;
          cfg.subDir = subDir;
          cfg.samples = 100000;
          cfg.rejectionCell = true;
          const test::Chi2Result r = test::jointChi2(m, mode, glm::normalize(wk), l, seed++, cfg);
          EXPECT_GT(r.p, 1e-3);
        }
  }
}

TEST(ZhdanovSampling, SampleMatchesPdfAndEval) {
  for (const auto& [name, params] : allParams()) {
    SCOPED_TRACE(name);
    const ZhdanovBdf m(params, kRange);
    Rng rng(5);
    int checked = 0;
    for (int i = 0; i < 20000; ++i) {
      const TransportMode mode = (i & 1) ? TransportMode::Radiance : TransportMode::Importance;
      const Vec3 wKnown = test::randomDirection(rng);
      const float lKnown = kRange.min + rng.uniform() * kRange.width();
      const std::optional<ScatterSample> s =
          m.sample(mode, wKnown, lKnown, Vec3(rng.uniform(), rng.uniform(), rng.uniform()));
      if (!s) continue;
      ++checked;
      const Event ev = physical(mode, wKnown, lKnown, s->w, s->lambda);
      const ScatterDensity d = m.pdf({mode, s->lobe, ev.lambdaIn, ev.lambdaOut}, ev.wi, ev.wo);
      EXPECT_TRUE(close(s->pdf, d.pdf, 1e-4)) << toString(mode) << " λ = " << lKnown;
      EXPECT_TRUE(close(s->pdfRev, d.pdfRev, 1e-4, 1e-30));
      const ScatterDensity back = m.pdf({flip(mode), s->lobe, ev.lambdaIn, ev.lambdaOut}, ev.wi, ev.wo);
      EXPECT_TRUE(close(d.pdfRev, back.pdf, 1e-6, 1e-30));
      EXPECT_TRUE(close(s->f, m.eval({mode, s->lobe, ev.lambdaIn, ev.lambdaOut}, ev.wi, ev.wo), 1e-6));
      EXPECT_GT(s->f, 0.0f);
    }
    EXPECT_GT(checked, 8000);
  }
}

// Spectral stage: the elastic probability plus ∫ fluorescent density dλ is 1 in both modes wherever
// anything scatters, 0 elsewhere; the directional stage integrates to 1 for the Lambert lobes and
// to 1 minus the rejected part of the gloss peak (checked against the χ² rejection cell above).
TEST(ZhdanovSampling, SpectralDensityIntegratesToOne) {
  for (const auto& [name, params] : allParams()) {
    SCOPED_TRACE(name);
    const ZhdanovBdf m(params, kRange);
    for (const TransportMode mode : {TransportMode::Radiance, TransportMode::Importance})
      for (const float l : {365.0f, 400.0f, 430.0f, 479.0f, 560.0f, 700.0f, 829.0f}) {
        double total = m.spectralPdf(mode, l, l, SpectralLobe::Elastic);
        for (int k = 0; k < 4700; ++k)
          total += 0.1 * m.spectralPdf(mode, l, float(kRange.min + (k + 0.5) * 0.1), SpectralLobe::Fluorescent);
        const bool scatters = m.gloss() + m.passive(l) + (mode == TransportMode::Importance ? m.A(l) : m.E(l)) > 0.0f;
        EXPECT_TRUE(close(total, scatters ? 1.0 : 0.0, 2e-4)) << toString(mode) << " λ = " << l;
      }
    const Vec3 wKnown = glm::normalize(Vec3(0.2f, 0.3f, 0.9f));
    const double fl = test::sphereIntegral(64, 32, [&](const Vec3& w) {
      return m.directionPdf({TransportMode::Radiance, SpectralLobe::Fluorescent, 420.0f, 560.0f}, wKnown, w);
    });
    EXPECT_TRUE(close(fl, 1.0, 1e-4));
    const double el = test::sphereIntegral(800, 128, [&](const Vec3& w) {
      return m.directionPdf({TransportMode::Importance, SpectralLobe::Elastic, 560.0f, 560.0f}, wKnown, w);
    });
    EXPECT_LE(el, 1.0 + 1e-3);
    if (m.gloss() == 0.0f) EXPECT_TRUE(close(el, 1.0, 1e-4));
  }
}

// Directional reciprocity: f(λ_i, ω_i, ω_o, λ_o) = f(λ_i, ω_o, ω_i, λ_o) for both lobes; the
// wavelengths are not exchangeable (fluorescence is not reciprocal in λ).
TEST(ZhdanovEnergy, DirectionallyReciprocalNotSpectrally) {
  const ZhdanovBdf m(glossyParams(), kRange);
  Rng rng(9);
  for (int i = 0; i < 2000; ++i) {
    const Vec3 a = test::randomDirection(rng), b = test::randomDirection(rng);
    const float l1 = 380.0f + 100.0f * rng.uniform(), l2 = 500.0f + 150.0f * rng.uniform();
    for (const SpectralLobe lobe : {SpectralLobe::Elastic, SpectralLobe::Fluorescent})
      EXPECT_TRUE(close(m.eval({TransportMode::Radiance, lobe, l1, l2}, a, b),
                        m.eval({TransportMode::Importance, lobe, l1, l2}, b, a), 1e-5, 1e-12));
  }
  EXPECT_GT(m.eval({TransportMode::Radiance, SpectralLobe::Fluorescent, 430.0f, 560.0f}, Vec3(0, 0, 1), Vec3(0, 0, 1)),
            0.0f);
  EXPECT_EQ(m.eval({TransportMode::Radiance, SpectralLobe::Fluorescent, 560.0f, 430.0f}, Vec3(0, 0, 1), Vec3(0, 0, 1)),
            0.0f);
}

// ∫_Ω ∫_Λ f cos θ_o dλ_o dω_o for light arriving along wi at λ_i: ρ_g·(Phong albedo) + p + A.
// At normal incidence the Phong albedo is exactly 1 (∫(n+2)/(2π) cos^(n+1) θ dω = 1).
double albedoIn(const ZhdanovBdf& m, const Vec3& wi, float li) {
  const double dl = 0.5;
  const int nL = int(kRange.width() / dl);
  double fl = 0.0;
  for (int k = 0; k < nL; ++k) fl += dl * m.E(float(kRange.min + (k + 0.5) * dl));
  fl *= m.A(li);  // ∫E dλ_o · A(λ_i); the fluorescent and passive lobes are Lambertian (albedo = π·f)
  return test::sphereIntegral(
             400, 64,
             [&](const Vec3& wo) {
               return m.eval({TransportMode::Radiance, SpectralLobe::Elastic, li, li}, wi, wo) * std::max(0.0f, wo.z);
             }) +
         fl;
}

TEST(ZhdanovEnergy, AlbedoIsGlossPlusPassivePlusExcitation) {
  for (const auto& [name, params] : allParams()) {
    SCOPED_TRACE(name);
    const ZhdanovBdf m(params, kRange);
    for (const float l : {400.0f, 430.0f, 560.0f, 700.0f}) {
      const double expected = m.gloss() + m.passive(l) + m.A(l);
      EXPECT_TRUE(close(albedoIn(m, Vec3(0, 0, 1), l), expected, 2e-3)) << "λ = " << l;
      const double oblique = albedoIn(m, glm::normalize(Vec3(0.8f, 0.0f, 0.4f)), l);
      EXPECT_LE(oblique, expected + 1e-3) << "λ = " << l;
      EXPECT_LE(oblique, 1.0 + 1e-3);
    }
  }
}

// White furnace of light paths: with ρ_g = 0 and p + A = 1 each sampled event in Importance mode
// carries weight f·cos/pdf = 1 exactly; in Radiance mode the weight is p(λ_o) + E(λ_o)·∫A.
TEST(ZhdanovEnergy, WhiteFurnaceWeights) {
  const ZhdanovBdf m(furnaceParams(), kRange);
  double intA = 0.0;
  for (int k = 0; k < 4700; ++k) intA += 0.1 * m.A(float(kRange.min + (k + 0.5) * 0.1));
  Rng rng(21);
  for (int i = 0; i < 5000; ++i) {
    const float l = kRange.min + rng.uniform() * kRange.width();
    const Vec3 w = test::randomDirection(rng);
    const Vec3 u(rng.uniform(), rng.uniform(), rng.uniform());
    if (const auto s = m.sample(TransportMode::Importance, w, l, u))
      EXPECT_TRUE(close(s->f * std::abs(s->w.z) / s->pdf, 1.0, 1e-4)) << "λ_i = " << l;
    if (const auto s = m.sample(TransportMode::Radiance, w, l, u))
      EXPECT_TRUE(close(s->f * std::abs(s->w.z) / s->pdf, m.passive(l) + m.E(l) * intA, 2e-3)) << "λ_o = " << l;
  }
}

TEST(ZhdanovParamsCheck, RejectsInvalidParameters) {
  EXPECT_EQ(checkZhdanovParams(glossyParams(), kRange), "");
  struct Case {
    const char* field;
    ZhdanovParams p;
  };
  std::vector<Case> cases;
  ZhdanovParams p = glossyParams();
  p.gloss = 1.2f;
  cases.push_back({"gloss:", p});
  p = glossyParams();
  p.glossExponent = -1.0f;
  cases.push_back({"gloss_exponent:", p});
  p = glossyParams();
  p.passive = Spectrum::constant(-0.1f);
  cases.push_back({"passive:", p});
  p = glossyParams();
  p.passive = Spectrum::constant(0.7f);  // 0.15 + 0.7 + 0.5 > 1 at 430 nm
  cases.push_back({"passive:", p});
  p = glossyParams();
  p.emission = Spectrum::constant(0.0f);
  cases.push_back({"emission:", p});
  for (const Case& c : cases) {
    const std::string msg = checkZhdanovParams(c.p, kRange);
    EXPECT_EQ(msg.rfind(c.field, 0), 0u) << msg;
    EXPECT_THROW(ZhdanovBdf(c.p, kRange), std::invalid_argument);
  }
  p = glossyParams();
  p.passive = Spectrum::constant(0.7f);
  p.allowUnphysical = true;
  EXPECT_EQ(checkZhdanovParams(p, kRange), "");
}

}  // namespace
}  // namespace kasha
