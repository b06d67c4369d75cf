// Unit tests of the Jung18 diffuse fluorescent BBRRDF (materials/jung_bbrrdf.h) and of the
// wavelength sampling it is built on (core/spectral_distribution.h): docs/validation.md §3.
//
// Every expected value is computed here, either by hand from the paper's formulas (eqs. 4–8) or
// by numerical quadrature of the material's own eval()/pdf(); none is copied from a run.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/rng.h"
#include "core/sampling.h"
#include "core/spectral_distribution.h"
#include "materials/jung_bbrrdf.h"
#include "tests/material_chi2.h"
#include "tests/material_support.h"
#include "tests/support.h"

namespace kasha {
namespace {

using test::close;
using test::Chi2Config;
using test::Chi2Result;
using test::Event;
using test::jointChi2;
using test::physical;
using test::sphereIntegral;
using test::dirFromCosPhi;
using test::randomDirection;

const WavelengthRange kRange{360.0f, 830.0f};

// ---------------------------------------------------------------------------------------------
// Parameter sets

// docs/validation.md §1's worked example: a = 0.8 on [400, 450), e a box on [550, 600), r = 0.5.
JungParams boxParams() {
  JungParams p;
  p.absorption = Spectrum::box(400.0f, 450.0f, 0.8f);
  p.emission = Spectrum::box(550.0f, 600.0f, 1.0f);  // normalised internally to 1/50
  p.reflectance = Spectrum::constant(0.5f);
  p.concentration = 1.0f;
  p.energyRatio = 0.9f;
  return p;
}

// c and Q strictly inside (0, 1), and a reflectance that is zero from 650 nm on, where the
// material then scatters nothing at all.
JungParams partialParams() {
  JungParams p = boxParams();
  p.reflectance = Spectrum::box(360.0f, 650.0f, 0.6f);
  p.concentration = 0.5f;
  p.energyRatio = 0.6f;
  return p;
}

// Overlapping absorption and emission (Gaussians), a sloped reflectance.
constexpr float kAbsCentre = 490.0f, kAbsFwhm = 40.0f, kAbsPeak = 0.9f;
constexpr float kEmCentre = 530.0f, kEmFwhm = 50.0f;
JungParams overlapParams() {
  JungParams p;
  p.absorption = Spectrum::gaussian(kAbsCentre, kAbsFwhm, kAbsPeak);  // tabulated over 370–610 nm
  p.emission = Spectrum::gaussian(kEmCentre, kEmFwhm, 1.0f);          // tabulated over 380–680 nm
  p.reflectance = Spectrum::piecewiseLinear({360.0f, 830.0f}, {0.3f, 0.7f});
  p.concentration = 0.6f;
  p.energyRatio = 0.7f;
  return p;
}

// c = 0: an ordinary diffuse reflector.
JungParams nonFluorescentParams() {
  JungParams p = boxParams();
  p.concentration = 0.0f;
  return p;
}

// Every bound of eq. 8 reached: all energy absorbed in the band is re-emitted, r = 1 elsewhere.
JungParams extremeParams() {
  JungParams p;
  p.absorption = Spectrum::box(400.0f, 450.0f, 1.0f);
  p.emission = Spectrum::box(550.0f, 600.0f, 3.0f);
  p.reflectance = Spectrum::constant(1.0f);
  p.concentration = 1.0f;
  p.energyRatio = 1.0f;
  return p;
}

struct NamedParams {
  const char* name;
  JungParams params;
};
std::vector<NamedParams> allParams() {
  return {{"box", boxParams()},
          {"partial", partialParams()},
          {"overlap", overlapParams()},
          {"non_fluorescent", nonFluorescentParams()},
          {"extreme", extremeParams()}};
}

// Helpers: tests/material_chi2.h (sphereIntegral, physical, jointChi2).

void runChi2(const JungParams& params, const std::vector<float>& knownLambdas, const std::vector<Vec3>& wKnowns) {
  const JungBbrrdf m(params, kRange);
  uint64_t seed = 1;
  for (const TransportMode mode : {TransportMode::Radiance, TransportMode::Importance})
    for (const float l : knownLambdas)
      for (const Vec3& wk : wKnowns) {
        SCOPED_TRACE(std::string(toString(mode)) + " known λ = " + std::to_string(l) + " nm, ω_known.z = " +
                     std::to_string(wk.z));
        const Chi2Config cfg;
        const Chi2Result r = jointChi2(m, mode, glm::normalize(wk), l, seed++, cfg);
        EXPECT_GT(r.p, 1e-3);
        // A sample can only fail when a direction coordinate u is exactly 0 (probability 2⁻²⁴ each):
        // the concentric map then lands on the disk's rim, at cos θ = 0.
        EXPECT_LE(r.failed, cfg.samples / 100000);
      }
}

TEST(JungBbrrdfChi2, BoxSpectraJointDirectionWavelength) {
  // inside the absorption band, in neither band, inside the emission band
  runChi2(boxParams(), {420.0f, 500.0f, 575.0f}, {Vec3(0.3f, -0.2f, 0.8f)});
}

TEST(JungBbrrdfChi2, PartialConcentrationAndEnergyRatio) {
  runChi2(partialParams(), {420.0f, 575.0f, 640.0f}, {Vec3(-0.5f, 0.1f, 0.4f)});
}

TEST(JungBbrrdfChi2, OverlappingGaussians) {
  runChi2(overlapParams(), {450.0f, 505.0f, 540.0f, 620.0f}, {Vec3(0.1f, 0.6f, 0.7f)});
}

TEST(JungBbrrdfChi2, NoFluorescenceWhenConcentrationIsZero) {
  runChi2(nonFluorescentParams(), {420.0f, 575.0f}, {Vec3(0.0f, 0.3f, 0.9f)});
}

TEST(JungBbrrdfChi2, KnownDirectionBelowTheSurface) {
  // Both sides of the surface reflect: samples must stay on the known direction's side.
  runChi2(overlapParams(), {500.0f}, {Vec3(0.2f, 0.4f, -0.6f)});
}

// Nothing scattered (r = 0, a = e = 0 at 700 nm): no sample, zero densities.
TEST(JungBbrrdfSampling, NothingScatteredGivesNoSample) {
  const JungBbrrdf m(partialParams(), kRange);
  ASSERT_EQ(m.albedoIn(700.0f), 0.0f);
  ASSERT_EQ(m.albedoOut(700.0f), 0.0f);
  Rng rng(3);
  for (const TransportMode mode : {TransportMode::Radiance, TransportMode::Importance}) {
    for (int i = 0; i < 1000; ++i)
      EXPECT_FALSE(m.sample(mode, Vec3(0, 0, 1), 700.0f, Vec3(rng.uniform(), rng.uniform(), rng.uniform())));
    EXPECT_EQ(m.spectralPdf(mode, 700.0f, 700.0f, SpectralLobe::Elastic), 0.0f);
    EXPECT_EQ(m.spectralPdf(mode, 700.0f, 420.0f, SpectralLobe::Fluorescent), 0.0f);
    EXPECT_EQ(m.spectralPdf(mode, 700.0f, 575.0f, SpectralLobe::Fluorescent), 0.0f);
  }
}

// ---------------------------------------------------------------------------------------------
// sample() agrees with pdf() and eval(), and its weight is the albedo (Jung18 §5: two-stage
// sampling gives the density proportional to f).

TEST(JungBbrrdfSampling, SampleMatchesPdfAndEval) {
  for (const NamedParams& np : allParams()) {
    SCOPED_TRACE(np.name);
    const JungBbrrdf m(np.params, kRange);
    Rng rng(11);
    int checked = 0, fluorescent = 0;
    for (int i = 0; i < 20000; ++i) {
      const TransportMode mode = (i & 1) ? TransportMode::Radiance : TransportMode::Importance;
      const Vec3 wKnown = randomDirection(rng);
      const float lKnown = kRange.min + rng.uniform() * kRange.width();
      const std::optional<ScatterSample> s =
          m.sample(mode, wKnown, lKnown, Vec3(rng.uniform(), rng.uniform(), rng.uniform()));
      const float albedo = mode == TransportMode::Radiance ? m.albedoOut(lKnown) : m.albedoIn(lKnown);
      if (!s) {
        EXPECT_EQ(albedo, 0.0f) << "λ = " << lKnown;
        continue;
      }
      ++checked;
      fluorescent += s->lobe == SpectralLobe::Fluorescent;
      EXPECT_GT(s->pdf, 0.0f);
      EXPECT_FALSE(s->specular);
      const Event ev = physical(mode, wKnown, lKnown, s->w, s->lambda);
      const ScatterDensity d = m.pdf({mode, s->lobe, ev.lambdaIn, ev.lambdaOut}, ev.wi, ev.wo);
      EXPECT_TRUE(close(s->pdf, d.pdf, 1e-4)) << toString(mode) << " λ = " << lKnown;
      EXPECT_TRUE(close(s->pdfRev, d.pdfRev, 1e-4, 1e-30)) << toString(mode) << " λ = " << lKnown;
      // The reverse density is the forward density of the other mode (one computation, two views).
      const ScatterDensity back = m.pdf({flip(mode), s->lobe, ev.lambdaIn, ev.lambdaOut}, ev.wi, ev.wo);
      EXPECT_TRUE(close(d.pdfRev, back.pdf, 1e-6, 1e-30));
      EXPECT_TRUE(close(d.pdf, back.pdfRev, 1e-6, 1e-30));
      EXPECT_TRUE(close(s->f, m.eval({mode, s->lobe, ev.lambdaIn, ev.lambdaOut}, ev.wi, ev.wo), 1e-6));
      // f·|cos θ_sampled| / pdf = albedoOut(λ_o) (camera paths) or albedoIn(λ_i) (light paths).
      EXPECT_TRUE(close(s->f * std::abs(s->w.z) / s->pdf, albedo, 1e-4)) << toString(mode) << " λ = " << lKnown;
    }
    EXPECT_GT(checked, 5000);
    if (m.fluoresces()) {
      EXPECT_GT(fluorescent, 100);
    } else {
      EXPECT_EQ(fluorescent, 0);
    }
  }
}

// ∫_S² ∫_Λ pdf dλ dω + elastic mass = 1 in both modes whenever anything is scattered.
TEST(JungBbrrdfSampling, DensityIntegratesToOne) {
  // Quadrature: 0.25 nm midpoints (box edges fall on cell edges, so exact for boxes; for the
  // Gaussians, tabulated at 0.4–0.5 nm, the error is below 1e-6), and directions exact (see
  // sphereIntegral). Float rounding of the summands stays below 1e-6 relative.
  const double dl = 0.25;
  const int nL = int(kRange.width() / dl);
  for (const NamedParams& np : allParams()) {
    SCOPED_TRACE(np.name);
    const JungBbrrdf m(np.params, kRange);
    const Vec3 wKnown = glm::normalize(Vec3(0.3f, 0.5f, 0.6f));
    for (const TransportMode mode : {TransportMode::Radiance, TransportMode::Importance})
      for (const float lKnown : {365.0f, 420.0f, 449.0f, 500.0f, 530.0f, 575.0f, 640.0f, 700.0f, 825.0f}) {
        const float albedo = mode == TransportMode::Radiance ? m.albedoOut(lKnown) : m.albedoIn(lKnown);
        const double total = sphereIntegral(8, 4, [&](const Vec3& w) {
          const Event ee = physical(mode, wKnown, lKnown, w, lKnown);
          double sum = m.pdf({mode, SpectralLobe::Elastic, ee.lambdaIn, ee.lambdaOut}, ee.wi, ee.wo).pdf;
          for (int k = 0; k < nL; ++k) {
            const Event ev = physical(mode, wKnown, lKnown, w, float(kRange.min + (k + 0.5) * dl));
            sum += dl * m.pdf({mode, SpectralLobe::Fluorescent, ev.lambdaIn, ev.lambdaOut}, ev.wi, ev.wo).pdf;
          }
          return sum;
        });
        if (albedo > 0.0f) {
          EXPECT_TRUE(close(total, 1.0, 2e-5)) << toString(mode) << " λ = " << lKnown;
        } else {
          EXPECT_EQ(total, 0.0) << toString(mode) << " λ = " << lKnown;
        }
      }
  }
}

// ---------------------------------------------------------------------------------------------
// Energy conservation (Jung18 eq. 8) and the reradiation matrix (eq. 5)

// ∫_Ω ∫_Λ f cos θ_o dλ_o dω_o (the elastic delta contributes its weight at λ_o = λ_i).
double numericAlbedoIn(const JungBbrrdf& m, const Vec3& wi, float lambdaIn, double dl) {
  const int nL = int(kRange.width() / dl);
  return sphereIntegral(4, 2, [&](const Vec3& wo) {
    double f = m.eval({TransportMode::Radiance, SpectralLobe::Elastic, lambdaIn, lambdaIn}, wi, wo);
    for (int k = 0; k < nL; ++k)
      f += dl *
           m.eval({TransportMode::Radiance, SpectralLobe::Fluorescent, lambdaIn, float(kRange.min + (k + 0.5) * dl)},
                  wi, wo);
    return f * std::abs(wo.z);
  });
}

// ∫_Ω ∫_Λ f cos θ_i dλ_i dω_i: energy leaving at λ_o under white incident light.
double numericAlbedoOut(const JungBbrrdf& m, const Vec3& wo, float lambdaOut, double dl) {
  const int nL = int(kRange.width() / dl);
  return sphereIntegral(4, 2, [&](const Vec3& wi) {
    double f = m.eval({TransportMode::Radiance, SpectralLobe::Elastic, lambdaOut, lambdaOut}, wi, wo);
    for (int k = 0; k < nL; ++k)
      f += dl *
           m.eval({TransportMode::Radiance, SpectralLobe::Fluorescent, float(kRange.min + (k + 0.5) * dl), lambdaOut},
                  wi, wo);
    return f * std::abs(wi.z);
  });
}

TEST(JungBbrrdfEnergy, Eq8HemisphericalSpectralAlbedoAtMostOne) {
  // Quadrature error: exact for boxes (0.5 nm cells, edges on cell edges); for the tabulated
  // Gaussian e, below 1e-5. Hence the 1e-4 slack on "≤ 1" and 1e-4 on agreement.
  for (const NamedParams& np : allParams()) {
    SCOPED_TRACE(np.name);
    const JungBbrrdf m(np.params, kRange);
    double maxAlbedo = 0.0;
    for (float li = 360.0f; li <= 830.0f; li += 5.0f)
      for (const Vec3& wi : {Vec3(0, 0, 1), glm::normalize(Vec3(0.7f, 0.2f, 0.1f)), glm::normalize(Vec3(0.1f, -0.3f, -0.8f))}) {
        const double num = numericAlbedoIn(m, wi, li, 0.5);
        EXPECT_LE(num, 1.0 + 1e-4) << "λ_i = " << li;
        EXPECT_TRUE(close(num, m.albedoIn(li), 1e-4, 1e-7)) << "λ_i = " << li;
        maxAlbedo = std::max(maxAlbedo, num);
      }
    if (std::string(np.name) == "extreme") {
      EXPECT_NEAR(maxAlbedo, 1.0, 1e-4);  // the bound is reached
    }
  }
}

TEST(JungBbrrdfEnergy, AlbedoOutMatchesIntegralOverIncidentSide) {
  for (const NamedParams& np : allParams()) {
    SCOPED_TRACE(np.name);
    const JungBbrrdf m(np.params, kRange);
    for (float lo = 362.5f; lo <= 830.0f; lo += 5.0f) {
      const Vec3 wo = glm::normalize(Vec3(-0.2f, 0.4f, 0.5f));
      EXPECT_TRUE(close(numericAlbedoOut(m, wo, lo, 0.5), m.albedoOut(lo), 1e-4, 1e-7)) << "λ_o = " << lo;
    }
  }
  // By hand, box spectra: albedoOut(575) = (1 − 0)·0.5 + c·Q·∫a·e(575) = 0.5 + 0.9·40·0.02 = 1.22
  // (not bounded by 1: it is the response to white light at all incident wavelengths).
  EXPECT_NEAR(JungBbrrdf(boxParams(), kRange).albedoOut(575.0f), 1.22, 1e-5);
  // albedoIn(420) = (1 − 0.8)·0.5 + 0.8·0.9 = 0.82
  EXPECT_NEAR(JungBbrrdf(boxParams(), kRange).albedoIn(420.0f), 0.82, 1e-6);
}

// Mass of the normalised emission e() in [lo, hi]: the interval is cut at the knots of the emission
// spectrum, and e is linear on each piece, so the midpoint rule on each piece is exact (up to
// float rounding of e, 1e-7 relative).
double emissionMass(const JungBbrrdf& m, const Spectrum& emission, float lo, float hi) {
  std::vector<float> cuts{lo};
  for (const float x : emission.lambdas())
    if (x > lo && x < hi) cuts.push_back(x);
  cuts.push_back(hi);
  double s = 0.0;
  for (size_t k = 0; k + 1 < cuts.size(); ++k)
    if (cuts[k + 1] > cuts[k]) s += m.e(0.5f * (cuts[k] + cuts[k + 1])) * double(cuts[k + 1] - cuts[k]);
  return s;
}

TEST(JungBbrrdfEnergy, ReradiationMatrixEq5) {
  std::vector<float> uniform;
  for (float l = 360.0f; l <= 830.0f; l += 2.5f) uniform.push_back(l);
  std::vector<float> irregular;  // sorted, uneven spacing
  Rng rng(5);
  for (float l = 360.0f; l <= 830.0f; l += 1.0f + 9.0f * rng.uniform()) irregular.push_back(l);

  for (const NamedParams& np : allParams()) {
    const JungBbrrdf m(np.params, kRange);
    for (const std::vector<float>* grid : {&uniform, &irregular}) {
      SCOPED_TRACE(std::string(np.name) + (grid == &uniform ? " uniform grid" : " irregular grid"));
      const ReradiationMatrix rm = m.reradiationMatrix(*grid);
      const size_t n = grid->size();
      // e_j: the mass of e in the band of grid[j], between the midpoints to its neighbours.
      std::vector<double> eBand(n);
      for (size_t j = 0; j < n; ++j) {
        const float lo = j == 0 ? kRange.min : 0.5f * ((*grid)[j - 1] + (*grid)[j]);
        const float hi = j + 1 == n ? kRange.max : 0.5f * ((*grid)[j] + (*grid)[j + 1]);
        eBand[j] = emissionMass(m, np.params.emission, lo, hi);
      }
      ASSERT_EQ(rm.grid, *grid);
      ASSERT_EQ(rm.m.size(), n);
      for (size_t i = 0; i < n; ++i) {
        ASSERT_EQ(rm.m[i].size(), n);
        const float li = (*grid)[i];
        double rowSum = 0.0;
        for (size_t j = 0; j < n; ++j) {
          // c·a_i·Q·e_j
          double expect = m.c() * m.a(li) * m.q() * eBand[j];
          if (i == j) expect += (1.0 - m.c() * m.a(li)) * m.r(li);  // R = diag((1 − c·a_i)·r_i)
          ASSERT_TRUE(close(rm.m[i][j], expect, 1e-4, 1e-7)) << "i = " << i << ", j = " << j;
          rowSum += rm.m[i][j];
        }
        EXPECT_NEAR(rowSum, m.albedoIn(li), 1e-3) << "λ = " << li;
        EXPECT_LE(rowSum, 1.0 + 1e-5) << "λ = " << li;
      }
    }
  }
  // By hand, box spectra on the uniform grid, row of 420 nm, column of 575 nm:
  // e_j = 2.5 nm × 1/50 = 0.05, so M = 1·0.8·0.9·0.05 = 0.036; diagonal at 500 nm: r = 0.5.
  const ReradiationMatrix box = JungBbrrdf(boxParams(), kRange).reradiationMatrix(uniform);
  const size_t i420 = size_t((420.0f - 360.0f) / 2.5f), i575 = size_t((575.0f - 360.0f) / 2.5f),
               i500 = size_t((500.0f - 360.0f) / 2.5f);
  EXPECT_NEAR(box.m[i420][i575], 0.036, 1e-6);
  EXPECT_NEAR(box.m[i500][i500], 0.5, 1e-6);
  EXPECT_EQ(box.m[i575][i420], 0.0f);
}

// ---------------------------------------------------------------------------------------------
// Reciprocity

TEST(JungBbrrdfReciprocity, DirectionsAreReciprocalForBothLobes) {
  Rng rng(17);
  for (const NamedParams& np : allParams()) {
    SCOPED_TRACE(np.name);
    const JungBbrrdf m(np.params, kRange);
    for (int i = 0; i < 2000; ++i) {
      const Vec3 a = randomDirection(rng), b = randomDirection(rng);
      const float l1 = kRange.min + rng.uniform() * kRange.width();
      const float l2 = kRange.min + rng.uniform() * kRange.width();
      for (const SpectralLobe lobe : {SpectralLobe::Elastic, SpectralLobe::Fluorescent}) {
        EXPECT_EQ(m.eval({TransportMode::Radiance, lobe, l1, l2}, a, b),
                  m.eval({TransportMode::Radiance, lobe, l1, l2}, b, a));
        if (a.z * b.z < 0.0f) {
          EXPECT_EQ(m.eval({TransportMode::Radiance, lobe, l1, l2}, a, b), 0.0f) << "no transmission";
        }
      }
      // The densities are reciprocal in direction too: pdf(a → b) in one mode = pdfRev.
      const ScatterDensity d = m.pdf({TransportMode::Importance, SpectralLobe::Elastic, l1, l1}, a, b);
      const ScatterDensity e = m.pdf({TransportMode::Radiance, SpectralLobe::Elastic, l1, l1}, a, b);
      EXPECT_TRUE(close(d.pdf, e.pdfRev, 1e-6, 1e-30));
    }
  }
}

TEST(JungBbrrdfReciprocity, WavelengthsAreNotReciprocal) {
  const Vec3 wi = glm::normalize(Vec3(0.2f, 0.1f, 0.9f)), wo = glm::normalize(Vec3(-0.4f, 0.3f, 0.7f));
  {
    // Box spectra: f(420 → 575) = c·a(420)·Q·e(575)/π = 1·0.8·0.9·(1/50)/π = 0.0144/π,
    // f(575 → 420) = c·a(575)·Q·e(420)/π = 0 (no absorption at 575 nm, no emission at 420 nm).
    const JungBbrrdf m(boxParams(), kRange);
    EXPECT_NEAR(m.eval({TransportMode::Radiance, SpectralLobe::Fluorescent, 420.0f, 575.0f}, wi, wo), 0.0144 / kPi,
                1e-7);
    EXPECT_EQ(m.eval({TransportMode::Radiance, SpectralLobe::Fluorescent, 575.0f, 420.0f}, wi, wo), 0.0f);
  }
  {
    // Overlapping Gaussians: both directions fluoresce, with different values.
    //   f(λ1 → λ2) = c·a(λ1)·Q·e(λ2)/π,  f(λ2 → λ1) = c·a(λ2)·Q·e(λ1)/π
    // with a(λ) = 0.9·G(λ; 490, σ_a), e(λ) = G(λ; 530, σ_e) / (σ_e·√(2π)), σ = FWHM / (2√(2 ln 2)).
    const JungBbrrdf m(overlapParams(), kRange);
    const double k = 2.0 * std::sqrt(2.0 * std::log(2.0));
    const double sa = kAbsFwhm / k, se = kEmFwhm / k;
    auto a = [&](double l) { return kAbsPeak * std::exp(-0.5 * sqr(float((l - kAbsCentre) / sa))); };
    auto e = [&](double l) { return std::exp(-0.5 * sqr(float((l - kEmCentre) / se))) / (se * std::sqrt(2.0 * kPi)); };
    const float l1 = 500.0f, l2 = 520.0f;
    const double f12 = 0.6 * a(l1) * 0.7 * e(l2) / kPi, f21 = 0.6 * a(l2) * 0.7 * e(l1) / kPi;
    // f12 ≈ 1.70e-3, f21 ≈ 1.75e-4: about a factor of 10 apart.
    ASSERT_GT(f12 / f21, 5.0);
    EXPECT_TRUE(close(m.eval({TransportMode::Radiance, SpectralLobe::Fluorescent, l1, l2}, wi, wo), f12, 2e-3));
    EXPECT_TRUE(close(m.eval({TransportMode::Radiance, SpectralLobe::Fluorescent, l2, l1}, wi, wo), f21, 2e-3));
    // Directions swapped, wavelengths kept: unchanged.
    EXPECT_EQ(m.eval({TransportMode::Radiance, SpectralLobe::Fluorescent, l1, l2}, wi, wo),
              m.eval({TransportMode::Radiance, SpectralLobe::Fluorescent, l1, l2}, wo, wi));
  }
}

// ---------------------------------------------------------------------------------------------
// Lobe probabilities (Jung18 eqs. 6 and 7)

TEST(JungBbrrdfLobeProbability, Eq6And7BoxSpectraByHand) {
  {
    // c = 1, Q = 0.9, a = 0.8 on [400, 450), e = 1/50 on [550, 600), r = 0.5, ∫a = 40.
    const JungBbrrdf m(boxParams(), kRange);
    // P_l(420) = 0.72 / (0.72 + 0.2·0.5) = 0.72 / 0.82
    EXPECT_NEAR(m.fluorescenceProbability(TransportMode::Importance, 420.0f), 0.8780488, 1e-6);
    EXPECT_NEAR(m.fluorescenceProbability(TransportMode::Importance, 500.0f), 0.0, 1e-7);  // no absorption
    EXPECT_NEAR(m.fluorescenceProbability(TransportMode::Importance, 575.0f), 0.0, 1e-7);
    // P_c(575) = 1·40·0.9·0.02 / (0.72 + 1·0.5) = 0.72 / 1.22
    EXPECT_NEAR(m.fluorescenceProbability(TransportMode::Radiance, 575.0f), 0.5901639, 1e-6);
    EXPECT_NEAR(m.fluorescenceProbability(TransportMode::Radiance, 420.0f), 0.0, 1e-7);  // no emission
    EXPECT_NEAR(m.fluorescenceProbability(TransportMode::Radiance, 500.0f), 0.0, 1e-7);
    // The spectral stage uses them: elastic mass 1 − P, fluorescent density P·a/∫a or P·e.
    EXPECT_NEAR(m.spectralPdf(TransportMode::Importance, 420.0f, 420.0f, SpectralLobe::Elastic), 0.1 / 0.82, 1e-6);
    EXPECT_NEAR(m.spectralPdf(TransportMode::Importance, 420.0f, 575.0f, SpectralLobe::Fluorescent),
                0.72 / 0.82 * 0.02, 1e-7);
    EXPECT_NEAR(m.spectralPdf(TransportMode::Radiance, 575.0f, 575.0f, SpectralLobe::Elastic), 0.5 / 1.22, 1e-6);
    EXPECT_NEAR(m.spectralPdf(TransportMode::Radiance, 575.0f, 420.0f, SpectralLobe::Fluorescent),
                0.72 / 1.22 * (0.8 / 40.0), 1e-7);
    EXPECT_EQ(m.spectralPdf(TransportMode::Radiance, 575.0f, 500.0f, SpectralLobe::Fluorescent), 0.0f);
  }
  {
    // c = 0.5, Q = 0.6, r = 0.6 below 650 nm and 0 above.
    const JungBbrrdf m(partialParams(), kRange);
    // P_l(420) = 0.5·0.8·0.6 / (0.24 + (1 − 0.4)·0.6) = 0.24 / 0.6
    EXPECT_NEAR(m.fluorescenceProbability(TransportMode::Importance, 420.0f), 0.4, 1e-6);
    // P_c(575) = 0.5·40·0.6·0.02 / (0.24 + 0.6) = 0.24 / 0.84
    EXPECT_NEAR(m.fluorescenceProbability(TransportMode::Radiance, 575.0f), 0.2857143, 1e-6);
    // Nothing reflected or emitted at 700 nm: both probabilities are defined as 0.
    EXPECT_EQ(m.fluorescenceProbability(TransportMode::Importance, 700.0f), 0.0f);
    EXPECT_EQ(m.fluorescenceProbability(TransportMode::Radiance, 700.0f), 0.0f);
  }
  {
    // Pure fluorescence at 575 nm on a camera path when r = 0 there: P_c = 1.
    JungParams p = boxParams();
    p.reflectance = Spectrum::constant(0.0f);
    const JungBbrrdf m(p, kRange);
    EXPECT_NEAR(m.fluorescenceProbability(TransportMode::Radiance, 575.0f), 1.0, 1e-7);
    EXPECT_NEAR(m.fluorescenceProbability(TransportMode::Importance, 420.0f), 1.0, 1e-7);
  }
  {
    const JungBbrrdf m(nonFluorescentParams(), kRange);
    EXPECT_EQ(m.fluorescenceProbability(TransportMode::Importance, 420.0f), 0.0f);
    EXPECT_EQ(m.fluorescenceProbability(TransportMode::Radiance, 575.0f), 0.0f);
    EXPECT_FALSE(m.fluoresces());
  }
}

TEST(JungBbrrdfLobeProbability, Eq6And7OverlappingGaussiansFromFormula) {
  // a, e and ∫a from the closed-form Gaussians (both tabulated over ±3 FWHM ≈ ±7σ inside the
  // range, so the truncated tails are < 1e-11); linear interpolation of the 0.4–0.5 nm tables
  // differs from the Gaussian by < 1e-4 relative.
  const JungBbrrdf m(overlapParams(), kRange);
  const double k = 2.0 * std::sqrt(2.0 * std::log(2.0));
  const double sa = kAbsFwhm / k, se = kEmFwhm / k;
  const double c = 0.6, q = 0.7;
  auto a = [&](double l) { return kAbsPeak * std::exp(-0.5 * ((l - kAbsCentre) / sa) * ((l - kAbsCentre) / sa)); };
  auto e = [&](double l) {
    return std::exp(-0.5 * ((l - kEmCentre) / se) * ((l - kEmCentre) / se)) / (se * std::sqrt(2.0 * kPi));
  };
  auto r = [](double l) { return 0.3 + 0.4 * (l - 360.0) / 470.0; };
  const double intA = kAbsPeak * sa * std::sqrt(2.0 * kPi);
  EXPECT_TRUE(close(m.absorptionIntegral(), intA, 1e-4));
  for (const double l : {430.0, 470.0, 490.0, 510.0, 530.0, 560.0, 600.0}) {
    const double pl = c * a(l) * q / (c * a(l) * q + (1.0 - c * a(l)) * r(l));
    const double pc = c * intA * q * e(l) / (c * intA * q * e(l) + (1.0 - c * a(l)) * r(l));
    EXPECT_TRUE(close(m.fluorescenceProbability(TransportMode::Importance, float(l)), pl, 1e-3)) << "λ = " << l;
    EXPECT_TRUE(close(m.fluorescenceProbability(TransportMode::Radiance, float(l)), pc, 1e-3)) << "λ = " << l;
  }
  // Outside both bands there is nothing to fluoresce.
  EXPECT_EQ(m.fluorescenceProbability(TransportMode::Importance, 700.0f), 0.0f);
  EXPECT_EQ(m.fluorescenceProbability(TransportMode::Radiance, 700.0f), 0.0f);
}

// ---------------------------------------------------------------------------------------------
// Parameter checks (eq. 8's conditions)

TEST(JungBbrrdfParams, AcceptsValidParameters) {
  for (const NamedParams& np : allParams()) {
    EXPECT_EQ(checkJungParams(np.params, kRange), "") << np.name;
    EXPECT_NO_THROW(JungBbrrdf(np.params, kRange)) << np.name;
  }
  // Values out of bounds only outside the wavelength range do not matter.
  JungParams p = boxParams();
  p.reflectance = Spectrum::piecewiseLinear({840.0f, 900.0f}, {1.5f, 1.5f}).zeroOutside();
  EXPECT_EQ(checkJungParams(p, kRange), "");
}

TEST(JungBbrrdfParams, RejectsInvalidParameters) {
  const float nan = std::numeric_limits<float>::quiet_NaN();
  struct Case {
    const char* what;
    const char* field;  // the message starts with "field:"
    std::function<void(JungParams&)> change;
  };
  const std::vector<Case> cases = {
      {"c < 0", "c:", [](JungParams& p) { p.concentration = -0.1f; }},
      {"c > 1", "c:", [](JungParams& p) { p.concentration = 1.01f; }},
      {"c NaN", "c:", [&](JungParams& p) { p.concentration = nan; }},
      {"Q < 0", "Q:", [](JungParams& p) { p.energyRatio = -0.5f; }},
      {"Q > 1", "Q:", [](JungParams& p) { p.energyRatio = 1.5f; }},
      {"Q NaN", "Q:", [&](JungParams& p) { p.energyRatio = nan; }},
      {"negative absorption", "absorption:",
       [](JungParams& p) { p.absorption = Spectrum::piecewiseLinear({400.0f, 500.0f, 600.0f}, {0.5f, -0.2f, 0.0f}); }},
      {"absorption > 1", "absorption:", [](JungParams& p) { p.absorption = Spectrum::box(400.0f, 450.0f, 1.2f); }},
      {"reflectance > 1", "reflectance:", [](JungParams& p) { p.reflectance = Spectrum::constant(1.2f); }},
      {"reflectance > 1 in a narrow peak", "reflectance:",
       [](JungParams& p) { p.reflectance = Spectrum::piecewiseLinear({500.0f, 510.0f, 520.0f}, {0.5f, 1.05f, 0.5f}); }},
      {"negative reflectance", "reflectance:", [](JungParams& p) { p.reflectance = Spectrum::constant(-0.1f); }},
      {"emission zero", "emission:", [](JungParams& p) { p.emission = Spectrum::constant(0.0f); }},
      {"emission outside the range", "emission:", [](JungParams& p) { p.emission = Spectrum::box(900.0f, 950.0f, 1.0f); }},
      {"negative emission", "emission:",
       [](JungParams& p) { p.emission = Spectrum::piecewiseLinear({500.0f, 550.0f, 600.0f}, {0.0f, 1.0f, -0.5f}); }},
  };
  for (const Case& cs : cases) {
    JungParams p = boxParams();
    cs.change(p);
    const std::string msg = checkJungParams(p, kRange);
    EXPECT_EQ(msg.rfind(cs.field, 0), 0u) << cs.what << ": got \"" << msg << "\"";
    EXPECT_THROW(JungBbrrdf(p, kRange), std::invalid_argument) << cs.what;
  }
}

// ---------------------------------------------------------------------------------------------
// SpectralDistribution: the wavelength sampler under both lobes' spectral stages.

double shapeMass(const Spectrum& s, double lo, double hi, double h) {
  const int n = std::max(1, int(std::lround((hi - lo) / h)));
  const double step = (hi - lo) / n;
  double sum = 0.0;
  for (int k = 0; k < n; ++k) sum += std::max(0.0f, s(float(lo + (k + 0.5) * step))) * step;
  return sum;
}

struct NamedSpectrum {
  const char* name;
  Spectrum s;
};
std::vector<NamedSpectrum> distributionShapes() {
  return {
      {"box", Spectrum::box(400.0f, 450.0f, 0.8f)},
      {"gaussian", Spectrum::gaussian(530.0f, 50.0f, 1.0f)},
      // steps up and down, a zero gap, constant extrapolation at both ends
      {"piecewise_steps", Spectrum::piecewiseLinear({380.0f, 420.0f, 420.0f, 500.0f, 560.0f, 560.0f, 600.0f, 600.0f,
                                                     700.0f, 760.0f},
                                                    {0.0f, 1.0f, 0.4f, 0.4f, 0.9f, 0.1f, 0.1f, 0.0f, 0.6f, 0.2f})},
      // clipped by the range: half of a Gaussian below 360 nm
      {"gaussian_clipped", Spectrum::gaussian(365.0f, 30.0f, 2.0f)},
  };
}

TEST(SpectralDistributionSampling, Chi2AgainstSpectrumShape) {
  // 2 nm bins; expected mass by 0.02 nm midpoints of the spectrum itself, normalised by the same
  // quadrature over the range (steps fall on bin edges or are crossed by one sub-cell: < 1e-5).
  const double bin = 2.0;
  const int nBins = int(kRange.width() / bin);
  const int n = 300000;
  uint64_t seed = 100;
  for (const NamedSpectrum& ns : distributionShapes()) {
    SCOPED_TRACE(ns.name);
    const SpectralDistribution dist(ns.s, kRange);
    std::vector<double> mass(nBins);
    double total = 0.0;
    for (int b = 0; b < nBins; ++b) total += mass[b] = shapeMass(ns.s, kRange.min + b * bin, kRange.min + (b + 1) * bin, 0.02);
    EXPECT_TRUE(close(dist.integral(), total, 1e-4));
    std::vector<double> observed(nBins + 1, 0.0), expected(nBins + 1, 0.0);  // last: outside the range
    for (int b = 0; b < nBins; ++b) expected[b] = n * mass[b] / total;
    Rng rng(seed++);
    for (int i = 0; i < n; ++i) {
      const WavelengthSample ws = dist.sample(rng.uniform());
      if (!(ws.lambda >= kRange.min && ws.lambda <= kRange.max)) {
        observed[nBins] += 1.0;
        continue;
      }
      EXPECT_GT(ws.pdf, 0.0f) << "λ = " << ws.lambda;
      EXPECT_EQ(ws.pdf, dist.pdf(ws.lambda));
      observed[std::clamp(int((ws.lambda - kRange.min) / bin), 0, nBins - 1)] += 1.0;
    }
    EXPECT_GT(test::chi2PValue(observed, expected), 1e-3);
  }
}

TEST(SpectralDistributionSampling, PdfIntegratesToOneAndIsZeroOutsideTheRange) {
  for (const NamedSpectrum& ns : distributionShapes()) {
    SCOPED_TRACE(ns.name);
    const SpectralDistribution dist(ns.s, kRange);
    // 0.01 nm midpoints: steps are crossed by one cell each (error ≤ 0.01·Δy/total < 1e-4).
    const double h = 0.01;
    double sum = 0.0;
    for (int k = 0; k < int(kRange.width() / h); ++k) sum += dist.pdf(float(kRange.min + (k + 0.5) * h)) * h;
    EXPECT_TRUE(close(sum, 1.0, 1e-4));
    EXPECT_EQ(dist.pdf(kRange.min - 1.0f), 0.0f);
    EXPECT_EQ(dist.pdf(kRange.max + 1.0f), 0.0f);
    // pdf ∝ spectrum inside the range
    for (float l = 361.0f; l < 830.0f; l += 7.0f)
      EXPECT_TRUE(close(dist.pdf(l), std::max(0.0f, ns.s(l)) / dist.integral(), 1e-6, 1e-12)) << "λ = " << l;
  }
  // Nothing to sample: zero density, zero-pdf samples.
  const SpectralDistribution empty(Spectrum::box(900.0f, 950.0f, 1.0f), kRange);
  EXPECT_EQ(empty.integral(), 0.0f);
  EXPECT_EQ(empty.sample(0.5f).pdf, 0.0f);
  EXPECT_EQ(empty.pdf(500.0f), 0.0f);
}

}  // namespace
}  // namespace kasha
