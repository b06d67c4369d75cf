// Unit tests of the coated fluorescent material (materials/coated_fluorescent.h, docs/layered.md):
// docs/validation.md §3 (joint χ² in both modes, densities, energy, reciprocity) and the limit where the
// coat has η = 1 and the material is Jung18's BBRRDF.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "core/error.h"
#include "core/rng.h"
#include "materials/coated_fluorescent.h"
#include "materials/fresnel.h"
#include "materials/material_json.h"
#include "tests/glossy_support.h"
#include "tests/material_chi2.h"
#include "tests/material_support.h"
#include "tests/support.h"

namespace kasha {
namespace {

using test::close;
using test::dirFromCosPhi;
using test::Event;
using test::physical;
using test::randomDirection;

const WavelengthRange kRange{360.0f, 830.0f};
const TransportMode kModes[] = {TransportMode::Radiance, TransportMode::Importance};

// docs/validation.md §1's box spectra, c and Q inside (0, 1).
JungParams boxParams() {
  JungParams p;
  p.absorption = Spectrum::box(400.0f, 450.0f, 0.8f);
  p.emission = Spectrum::box(550.0f, 600.0f, 1.0f);
  p.reflectance = Spectrum::box(360.0f, 650.0f, 0.6f);
  p.concentration = 0.7f;
  p.energyRatio = 0.8f;
  return p;
}

// Every bound of Jung18 eq. 8 reached: the base alone conserves energy exactly.
JungParams extremeParams() {
  JungParams p;
  p.absorption = Spectrum::box(400.0f, 450.0f, 1.0f);
  p.emission = Spectrum::box(550.0f, 600.0f, 1.0f);
  p.reflectance = Spectrum::constant(1.0f);
  p.concentration = 1.0f;
  p.energyRatio = 1.0f;
  return p;
}

// ---------------------------------------------------------------------------------------------
// Sampling

TEST(CoatedFluorescentChi2, JointDirectionWavelengthBothModes) {
  const CoatedFluorescent m(boxParams(), *Ior::preset("BK7"), 0.3f, 0.3f, kRange);
  test::Chi2Config cfg;
  cfg.range = kRange;
  cfg.subDir = 6;
  cfg.samples = 200000;
  uint64_t seed = 1;
  // inside the absorption band, inside the emission band, where r = 0 (only the coat reflects)
  for (const TransportMode mode : kModes)
    for (const float l : {420.0f, 575.0f, 700.0f})
      for (const Vec3& w : {glm::normalize(Vec3(0.3f, -0.2f, 0.8f)), glm::normalize(Vec3(-0.5f, 0.4f, -0.3f))}) {
        const test::Chi2Result r = test::jointChi2(m, mode, w, l, seed++, cfg);
        EXPECT_GT(r.p, 1e-3) << toString(mode) << " λ = " << l << ", w.z = " << w.z;
        // Failures (the coat mirroring below the surface) are the missing density mass: binomial
        // at 4σ plus 0.2% of n for the quadrature error of that mass.
        const double n = cfg.samples, pFail = std::max(0.0, 1.0 - r.expectedMass);
        EXPECT_NEAR(r.failed, n * pFail, 4.0 * std::sqrt(n * pFail * (1.0 - pFail)) + 2e-3 * n)
            << toString(mode) << " λ = " << l << ", w.z = " << w.z;
      }
}

TEST(CoatedFluorescentSampling, SampleMatchesPdfAndEval) {
  const CoatedFluorescent m(boxParams(), Ior::constant(1.5), 0.2f, 0.5f, kRange);
  Rng rng(11);
  int fluorescent = 0, checked = 0;
  for (int i = 0; i < 20000; ++i) {
    const TransportMode mode = kModes[i & 1];
    const Vec3 wKnown = randomDirection(rng);
    const float lKnown = 380.0f + 300.0f * rng.uniform();
    const std::optional<ScatterSample> s = m.sample(mode, wKnown, lKnown, Vec3(rng.uniform(), rng.uniform(), rng.uniform()));
    if (!s) continue;
    ++checked;
    fluorescent += s->lobe == SpectralLobe::Fluorescent;
    EXPECT_FALSE(s->specular);
    EXPECT_GT(s->w.z * wKnown.z, 0.0f);
    const Event ev = physical(mode, wKnown, lKnown, s->w, s->lambda);
    const ScatterDensity d = m.pdf({mode, s->lobe, ev.lambdaIn, ev.lambdaOut}, ev.wi, ev.wo);
    EXPECT_TRUE(close(s->pdf, d.pdf, 1e-4));
    EXPECT_TRUE(close(s->pdfRev, d.pdfRev, 1e-4, 1e-30));
    EXPECT_EQ(d.pdfRev, m.pdf({flip(mode), s->lobe, ev.lambdaIn, ev.lambdaOut}, ev.wi, ev.wo).pdf);
    EXPECT_TRUE(close(s->f, m.eval({mode, s->lobe, ev.lambdaIn, ev.lambdaOut}, ev.wi, ev.wo), 1e-6));
  }
  EXPECT_GT(checked, 15000);
  EXPECT_GT(fluorescent, 500);
}

// ---------------------------------------------------------------------------------------------
// Values

TEST(CoatedFluorescentEval, ByHandReciprocalAndModeFree) {
  const CoatedFluorescent m(boxParams(), Ior::constant(1.5), 0.3f, 0.3f, kRange);
  // Base terms by hand, Fresnel from fresnel.h (tested against Fresnel's trigonometric form).
  const Vec3 wi = dirFromCosPhi(0.8f, 0.0f), wo = dirFromCosPhi(0.5f, 2.0f);
  const double ti = 1.0 - fresnelDielectric(0.8f, 1.5f), to = 1.0 - fresnelDielectric(0.5f, 1.5f);
  // fluorescent 420 → 575: T_i·T_o/η²·c·a·Q·e/π = ·0.7·0.8·0.8·(1/50)/π
  EXPECT_TRUE(close(m.eval({TransportMode::Radiance, SpectralLobe::Fluorescent, 420.0f, 575.0f}, wi, wo),
                    ti * to / 2.25 * 0.7 * 0.8 * 0.8 * 0.02 / kPi, 1e-5));
  // elastic at 500 nm (no absorption): T_i·T_o/η²·r/π plus the coat's GGX reflection
  const Vec3 h = reflectionHalfVector(wi, wo);
  const double coat = fresnelDielectric(std::abs(glm::dot(wi, h)), 1.5f) * m.ggx().reflection(wi, wo);
  EXPECT_TRUE(close(m.eval({TransportMode::Radiance, SpectralLobe::Elastic, 500.0f, 500.0f}, wi, wo),
                    ti * to / 2.25 * 0.6 / kPi + coat, 1e-5));
  // Reciprocal in directions, not in wavelengths; one value in both modes.
  Rng rng(4);
  for (int i = 0; i < 3000; ++i) {
    const Vec3 a = randomDirection(rng), b = randomDirection(rng);
    const float l1 = 380.0f + 300.0f * rng.uniform(), l2 = 380.0f + 300.0f * rng.uniform();
    for (const SpectralLobe lobe : {SpectralLobe::Elastic, SpectralLobe::Fluorescent}) {
      const float fab = m.eval({TransportMode::Radiance, lobe, l1, l2}, a, b);
      EXPECT_TRUE(close(fab, m.eval({TransportMode::Radiance, lobe, l1, l2}, b, a), 1e-5));
      EXPECT_EQ(fab, m.eval({TransportMode::Importance, lobe, l1, l2}, a, b));
    }
  }
  EXPECT_GT(m.eval({TransportMode::Radiance, SpectralLobe::Fluorescent, 420.0f, 575.0f}, wi, wo), 0.0f);
  EXPECT_EQ(m.eval({TransportMode::Radiance, SpectralLobe::Fluorescent, 575.0f, 420.0f}, wi, wo), 0.0f);
}

// ---------------------------------------------------------------------------------------------
// Energy: ∫∫ f·cos θ_o dλ_o dω_o ≤ 1 for every incident (ω_i, λ_i), by quadrature, and equal to
// the mean weight of Importance-mode samples (which sample exactly this integral).

double albedoIn(const CoatedFluorescent& m, const Vec3& wi, float li) {
  // Elastic part on a fine direction grid (the GGX lobe); the fluorescent part, smooth in
  // direction, on a coarse one with 1 nm midpoints over the box emission (exact in λ).
  const double elastic = test::sphereQuadrature(1000, 300, [&](const Vec3& wo) {
    return m.eval({TransportMode::Importance, SpectralLobe::Elastic, li, li}, wi, wo) * std::abs(wo.z);
  });
  const double fluorescent = test::sphereQuadrature(200, 8, [&](const Vec3& wo) {
    double fl = 0.0;
    for (float lo = 550.5f; lo < 600.0f; lo += 1.0f)
      fl += m.eval({TransportMode::Importance, SpectralLobe::Fluorescent, li, lo}, wi, wo);
    return fl * std::abs(wo.z);
  });
  return elastic + fluorescent;
}

TEST(CoatedFluorescentEnergy, AlbedoAtMostOneAndMatchesSampling) {
  uint64_t seed = 70;
  for (const float eta : {1.05f, 1.5f, 2.4f})
    for (const float alpha : {0.05f, 0.5f}) {
      const CoatedFluorescent m(extremeParams(), Ior::constant(eta), alpha, alpha, kRange);
      for (const float cosI : {0.95f, 0.5f, 0.15f})
        for (const float li : {420.0f, 500.0f}) {
          const Vec3 wi = dirFromCosPhi(cosI, 1.0f);
          const double quad = albedoIn(m, wi, li);
          EXPECT_LE(quad, 1.0 + 1e-3) << "η = " << eta << ", α = " << alpha << ", cos θ_i = " << cosI;
          const test::BatchStats st = test::sampledAlbedo(m, TransportMode::Importance, wi, li, seed++);
          EXPECT_NEAR(st.mean, quad, 4.0 * st.stderr_ + 3e-3)
              << "η = " << eta << ", α = " << alpha << ", cos θ_i = " << cosI << ", λ_i = " << li;
        }
    }
}

// ---------------------------------------------------------------------------------------------
// With η = 1 the coat vanishes: values, densities and samples are the base's.

TEST(CoatedFluorescentLimit, IndexOneIsTheBase) {
  const CoatedFluorescent m(boxParams(), Ior::constant(1.0), 0.3f, 0.3f, kRange);
  const JungModel& base = m.base();
  Rng rng(13);
  for (int i = 0; i < 5000; ++i) {
    const Vec3 a = randomDirection(rng), b = randomDirection(rng);
    const float l1 = 380.0f + 300.0f * rng.uniform(), l2 = 380.0f + 300.0f * rng.uniform();
    for (const TransportMode mode : kModes) {
      for (const SpectralLobe lobe : {SpectralLobe::Elastic, SpectralLobe::Fluorescent}) {
        EXPECT_FLOAT_EQ(m.eval({mode, lobe, l1, l2}, a, b), base.eval({mode, lobe, l1, l2}, a, b));
        EXPECT_FLOAT_EQ(m.spectralPdf(mode, l1, l2, lobe), base.spectralPdf(mode, l1, l2, lobe));
        EXPECT_FLOAT_EQ(m.directionPdf({mode, lobe, l1, l2}, a, b), base.directionPdf({mode, lobe, l1, l2}, a, b));
      }
      const Vec3 u(rng.uniform(), rng.uniform(), rng.uniform());
      const std::optional<ScatterSample> sm = m.sample(mode, a, l1, u), sb = base.sample(mode, a, l1, u);
      ASSERT_EQ(bool(sm), bool(sb));
      if (!sm) continue;
      EXPECT_EQ(sm->lobe, sb->lobe);
      EXPECT_EQ(sm->lambda, sb->lambda);
      EXPECT_EQ(sm->w, sb->w);
      EXPECT_FLOAT_EQ(sm->pdf, sb->pdf);
      EXPECT_FLOAT_EQ(sm->f, sb->f);
    }
  }
}

// ---------------------------------------------------------------------------------------------
// Scene-file form

TEST(CoatedFluorescentJson, ParsesAndRejects) {
  const SpectrumContext ctx{"scene.json", ".", nullptr};
  const nlohmann::json ok = {{"type", "coated_fluorescent"}, {"absorption", 0.5}, {"emission", 1.0},
                             {"reflectance", 0.4}, {"c", 0.5}, {"Q", 0.8}, {"coat_ior", 1.5}, {"coat_alpha", 0.1}};
  const auto m = parseMaterial(ok, ctx, "/materials/m", kRange);
  const auto* cf = dynamic_cast<const CoatedFluorescent*>(m.get());
  ASSERT_NE(cf, nullptr);
  EXPECT_EQ(cf->ggx().alphaX(), 0.1f);
  EXPECT_EQ(cf->coatIor()(500.0f), 1.5f);
  const auto error = [&](const nlohmann::json& v) -> std::string {
    try {
      parseMaterial(v, ctx, "/materials/m", kRange);
    } catch (const InputError& e) {
      return e.what();
    }
    return "no error";
  };
  const std::string at = "scene.json: /materials/m";
  nlohmann::json bad = ok;
  bad["coat_ior"] = 0.5;
  EXPECT_EQ(error(bad), at + "/coat_ior: index of refraction 0.500000 is below 1");
  bad = ok;
  bad.erase("coat_alpha");
  EXPECT_EQ(error(bad), at + "/coat_alpha: missing required field");
  bad = ok;
  bad["Q"] = 1.5;
  EXPECT_EQ(error(bad), at + "/Q: energy ratio 1.500000 is outside [0, 1]");
}

}  // namespace
}  // namespace kasha
