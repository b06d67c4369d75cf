// Unit tests of the Lambertian reflector (materials/lambertian.h): docs/validation.md §3 for a material
// with one elastic lobe. Expected values come from f = r(λ)/π and numerical quadrature of pdf().
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "core/rng.h"
#include "core/sampling.h"
#include "materials/lambertian.h"
#include "tests/material_support.h"
#include "tests/support.h"

namespace kasha {
namespace {

using test::close;
using test::dirFromCosPhi;
using test::randomDirection;

const WavelengthRange kRange{360.0f, 830.0f};

// Steps up and down, and zero from 760 nm on (nothing reflected there).
Spectrum steppedReflectance() {
  return Spectrum::piecewiseLinear({400.0f, 500.0f, 500.0f, 700.0f, 760.0f, 760.0f}, {0.2f, 0.8f, 0.4f, 0.6f, 0.6f, 0.0f});
}

struct Event {
  Vec3 wi, wo;
  float lambdaIn, lambdaOut;
};
Event physical(TransportMode mode, const Vec3& wKnown, float lKnown, const Vec3& wOther, float lOther) {
  if (mode == TransportMode::Radiance) return {wOther, wKnown, lOther, lKnown};
  return {wKnown, wOther, lKnown, lOther};
}

// χ² of sampled directions over the whole sphere, cells in (cos θ ∈ [−1, 1], φ); expected counts
// integrate Material::pdf over each cell on a 4×4 midpoint sub-grid. The lobe is always elastic
// and the wavelength the known one, which the loop asserts.
TEST(LambertianChi2, DirectionsBothModesBothSides) {
  const Lambertian m(steppedReflectance());
  const int nCos = 16, nPhi = 16, sub = 4, n = 300000;
  uint64_t seed = 1;
  for (const TransportMode mode : {TransportMode::Radiance, TransportMode::Importance})
    for (const Vec3& wk : {Vec3(0.3f, -0.2f, 0.8f), Vec3(0.9f, 0.1f, 0.05f), Vec3(-0.2f, 0.5f, -0.7f)})
      for (const float lKnown : {450.0f, 600.0f}) {
        const Vec3 wKnown = glm::normalize(wk);
        SCOPED_TRACE(std::string(toString(mode)) + " ω_known.z = " + std::to_string(wKnown.z) + " λ = " +
                     std::to_string(lKnown));
        std::vector<double> observed(nCos * nPhi, 0.0), expected(nCos * nPhi, 0.0);
        Rng rng(seed++, 3);
        int failed = 0;
        for (int i = 0; i < n; ++i) {
          const std::optional<ScatterSample> s =
              m.sample(mode, wKnown, lKnown, Vec3(rng.uniform(), rng.uniform(), rng.uniform()));
          if (!s) {
            ++failed;
            continue;
          }
          ASSERT_EQ(s->lobe, SpectralLobe::Elastic);
          ASSERT_EQ(s->lambda, lKnown);
          const int ic = std::clamp(int((s->w.z + 1.0f) * 0.5f * nCos), 0, nCos - 1);
          float phi = std::atan2(s->w.y, s->w.x);
          if (phi < 0.0f) phi += 2.0f * kPi;
          const int ip = std::clamp(int(phi / (2.0f * kPi) * nPhi), 0, nPhi - 1);
          observed[ic * nPhi + ip] += 1.0;
        }
        // Only u exactly 0 (probability 2⁻²⁴ per coordinate) can fail: the disk's rim, cos θ = 0.
        EXPECT_LE(failed, n / 100000);
        const double dc = 2.0 / nCos, dp = 2.0 * kPi / nPhi;
        for (int ic = 0; ic < nCos; ++ic)
          for (int ip = 0; ip < nPhi; ++ip)
            for (int a = 0; a < sub; ++a)
              for (int b = 0; b < sub; ++b) {
                const Vec3 w = dirFromCosPhi(float(-1.0 + dc * (ic + (a + 0.5) / sub)), float(dp * (ip + (b + 0.5) / sub)));
                const Event ev = physical(mode, wKnown, lKnown, w, lKnown);
                expected[ic * nPhi + ip] +=
                    n * (dc / sub) * (dp / sub) *
                    m.pdf({mode, SpectralLobe::Elastic, ev.lambdaIn, ev.lambdaOut}, ev.wi, ev.wo).pdf;
              }
        EXPECT_GT(test::chi2PValue(observed, expected), 1e-3);
      }
}

TEST(LambertianSampling, SampleMatchesPdfAndEval) {
  const Lambertian m(steppedReflectance());
  Rng rng(9);
  int checked = 0;
  for (int i = 0; i < 20000; ++i) {
    const TransportMode mode = (i & 1) ? TransportMode::Radiance : TransportMode::Importance;
    const Vec3 wKnown = randomDirection(rng);
    const float lKnown = kRange.min + rng.uniform() * kRange.width();
    const std::optional<ScatterSample> s = m.sample(mode, wKnown, lKnown, Vec3(rng.uniform(), rng.uniform(), rng.uniform()));
    const float r = m.reflectance()(lKnown);
    if (!s) {
      EXPECT_EQ(r, 0.0f) << "λ = " << lKnown;
      continue;
    }
    ++checked;
    EXPECT_EQ(s->lobe, SpectralLobe::Elastic);
    EXPECT_EQ(s->lambda, lKnown);
    EXPECT_FALSE(s->specular);
    EXPECT_GT(s->w.z * wKnown.z, 0.0f) << "reflection stays on the known side";
    const Event ev = physical(mode, wKnown, lKnown, s->w, s->lambda);
    const ScatterDensity d = m.pdf({mode, SpectralLobe::Elastic, ev.lambdaIn, ev.lambdaOut}, ev.wi, ev.wo);
    EXPECT_TRUE(close(s->pdf, d.pdf, 1e-4));
    EXPECT_TRUE(close(s->pdfRev, d.pdfRev, 1e-4));
    // cosine-weighted both ways: pdf = |cos θ_sampled|/π, pdfRev = |cos θ_known|/π
    EXPECT_TRUE(close(s->pdf, std::abs(s->w.z) / kPi, 1e-5));
    EXPECT_TRUE(close(s->pdfRev, std::abs(wKnown.z) / kPi, 1e-5));
    EXPECT_TRUE(close(s->f, m.eval({mode, SpectralLobe::Elastic, ev.lambdaIn, ev.lambdaOut}, ev.wi, ev.wo), 1e-6));
    EXPECT_TRUE(close(s->f, r / kPi, 1e-6));
    // weight f·|cos|/pdf = r(λ) exactly (perfect importance sampling)
    EXPECT_TRUE(close(s->f * std::abs(s->w.z) / s->pdf, r, 1e-5));
  }
  EXPECT_GT(checked, 15000);
}

TEST(LambertianSampling, DensityIntegratesToOne) {
  // Midpoint rule in (cos θ, φ): exact for a density linear in cos θ.
  const Lambertian m(steppedReflectance());
  const int nCos = 32, nPhi = 8;
  const double dc = 2.0 / nCos, dp = 2.0 * kPi / nPhi;
  for (const TransportMode mode : {TransportMode::Radiance, TransportMode::Importance})
    for (const Vec3& wk : {Vec3(0, 0, 1), Vec3(0.5f, 0.5f, -0.2f)})
      for (const float l : {450.0f, 790.0f}) {
        const Vec3 wKnown = glm::normalize(wk);
        double total = 0.0;
        for (int i = 0; i < nCos; ++i)
          for (int j = 0; j < nPhi; ++j) {
            const Event ev = physical(mode, wKnown, l, dirFromCosPhi(float(-1.0 + (i + 0.5) * dc), float((j + 0.5) * dp)), l);
            total += dc * dp * m.pdf({mode, SpectralLobe::Elastic, ev.lambdaIn, ev.lambdaOut}, ev.wi, ev.wo).pdf;
          }
        if (m.reflectance()(l) > 0.0f) {
          EXPECT_NEAR(total, 1.0, 1e-5) << toString(mode) << " λ = " << l;
        } else {
          EXPECT_EQ(total, 0.0) << toString(mode) << " λ = " << l;
        }
      }
}

TEST(LambertianEval, ValueIsReflectanceOverPiAndNoTransmission) {
  const Lambertian m(steppedReflectance());
  EXPECT_EQ(m.flags(), BsdfFlags::None);
  // By hand: r(450) = 0.2 + 0.6·(50/100) = 0.5; r(500) = 0.4 (right value of the step);
  // r(600) = 0.4 + 0.2·(100/200) = 0.5; r(800) = 0.
  const Vec3 up1 = glm::normalize(Vec3(0.1f, 0.2f, 0.9f)), up2 = glm::normalize(Vec3(-0.6f, 0.3f, 0.2f));
  const Vec3 down1 = glm::normalize(Vec3(0.4f, -0.1f, -0.8f)), down2 = glm::normalize(Vec3(-0.3f, -0.3f, -0.4f));
  EXPECT_NEAR(m.eval({TransportMode::Radiance, SpectralLobe::Elastic, 450.0f, 450.0f}, up1, up2), 0.5 / kPi, 1e-7);
  EXPECT_NEAR(m.eval({TransportMode::Radiance, SpectralLobe::Elastic, 500.0f, 500.0f}, up1, up2), 0.4 / kPi, 1e-7);
  // two-sided
  EXPECT_NEAR(m.eval({TransportMode::Radiance, SpectralLobe::Elastic, 600.0f, 600.0f}, down1, down2), 0.5 / kPi, 1e-7);
  EXPECT_EQ(m.eval({TransportMode::Radiance, SpectralLobe::Elastic, 800.0f, 800.0f}, up1, up2), 0.0f);
  // Opposite hemispheres: no transmission, and no density for it.
  for (const TransportMode mode : {TransportMode::Radiance, TransportMode::Importance}) {
    EXPECT_EQ(m.eval({mode, SpectralLobe::Elastic, 450.0f, 450.0f}, up1, down1), 0.0f);
    EXPECT_EQ(m.eval({mode, SpectralLobe::Elastic, 450.0f, 450.0f}, down2, up2), 0.0f);
    const ScatterDensity d = m.pdf({mode, SpectralLobe::Elastic, 450.0f, 450.0f}, up1, down1);
    EXPECT_EQ(d.pdf, 0.0f);
    EXPECT_EQ(d.pdfRev, 0.0f);
    // No fluorescent lobe.
    EXPECT_EQ(m.eval({mode, SpectralLobe::Fluorescent, 450.0f, 600.0f}, up1, up2), 0.0f);
    EXPECT_EQ(m.spectralPdf(mode, 450.0f, 600.0f, SpectralLobe::Fluorescent), 0.0f);
    EXPECT_EQ(m.spectralPdf(mode, 450.0f, 450.0f, SpectralLobe::Elastic), 1.0f);
    EXPECT_EQ(m.spectralPdf(mode, 800.0f, 800.0f, SpectralLobe::Elastic), 0.0f);
  }
  // Reciprocal in direction.
  Rng rng(21);
  for (int i = 0; i < 1000; ++i) {
    const Vec3 a = randomDirection(rng), b = randomDirection(rng);
    const float l = kRange.min + rng.uniform() * kRange.width();
    EXPECT_EQ(m.eval({TransportMode::Radiance, SpectralLobe::Elastic, l, l}, a, b),
              m.eval({TransportMode::Radiance, SpectralLobe::Elastic, l, l}, b, a));
  }
}

TEST(LambertianSampling, NothingReflectedGivesNoSample) {
  const Lambertian m(steppedReflectance());
  Rng rng(4);
  for (const TransportMode mode : {TransportMode::Radiance, TransportMode::Importance})
    for (int i = 0; i < 1000; ++i)
      EXPECT_FALSE(m.sample(mode, Vec3(0, 0, 1), 800.0f, Vec3(rng.uniform(), rng.uniform(), rng.uniform())));
}


TEST(LambertianSampling, SpectralDensityIsOneExactlyWhereSomethingIsReflected) {
  // A spectrum positive everywhere (answered without a lookup) and one with zeros, scaled by a
  // texel of 0 and of 1/2: the density of the elastic event is 1 where r(λ) > 0, else 0.
  const Spectrum positive = Spectrum::piecewiseLinear({400.0f, 600.0f}, {0.1f, 0.9f});
  const Spectrum stepped = steppedReflectance();
  for (const Spectrum* s : {&positive, &stepped})
    for (const float scale : {0.0f, 0.5f}) {
      HitReflectance r{s};
      r.scale = scale;
      const LambertianModel m(r);
      for (float l = 360.0f; l <= 830.0f; l += 1.3f) {
        const float expected = scale * (*s)(l) > 0.0f ? 1.0f : 0.0f;
        EXPECT_EQ(m.spectralPdf(TransportMode::Radiance, l, l, SpectralLobe::Elastic), expected) << l;
        EXPECT_EQ(m.sampleSpectral(TransportMode::Importance, l, 0.5f).pdf, expected) << l;
      }
    }
}

}  // namespace
}  // namespace kasha
