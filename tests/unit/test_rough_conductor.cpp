// Unit tests of the GGX distribution (materials/ggx.h) and the rough conductor
// (materials/rough_conductor.h): docs/validation.md §3 for a glossy elastic lobe. Expected values come
// from quadrature of the material's own functions or from the formulas in the headers' comments.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "core/error.h"
#include "core/rng.h"
#include "materials/material_json.h"
#include "materials/mirror.h"
#include "materials/rough_conductor.h"
#include "materials/specular_lobe.h"
#include "tests/glossy_support.h"
#include "tests/material_support.h"
#include "tests/support.h"

namespace kasha {
namespace {

using test::close;
using test::dirFromCosPhi;
using test::randomDirection;

const TransportMode kModes[] = {TransportMode::Radiance, TransportMode::Importance};

// A coloured F0 (gold-like: low in the blue, high in the red).
Spectrum goldF0() { return Spectrum::piecewiseLinear({400.0f, 500.0f, 600.0f, 700.0f}, {0.35f, 0.45f, 0.9f, 0.95f}); }

// Schlick's Fresnel of goldF0 at cos θ = c, written out here (Schlick 1994 eq. 15).
double goldSchlick(double c, float lambda) {
  const double f0 = goldF0()(lambda);
  return f0 + (1.0 - f0) * std::pow(1.0 - c, 5.0);
}

// Known directions on both sides, near-normal to grazing.
std::vector<Vec3> knownDirections() {
  std::vector<Vec3> ws;
  for (const float c : {0.95f, 0.6f, 0.25f})
    for (const float side : {1.0f, -1.0f}) ws.push_back(dirFromCosPhi(side * c, 0.4f + 2.0f * c));
  return ws;
}

// ---------------------------------------------------------------------------------------------
// The distribution

TEST(GgxDistribution, ProjectedAreaAndVisibleNormalsAreNormalised) {
  // ∫ D(m)·m_z dm = 1 (the microsurface projects onto the macro surface), and
  // ∫ D_w(m) dm = 1 for every w, which holds only with the matching Smith Λ (Heitz14).
  for (const Vec2 a : {Vec2(0.1f), Vec2(0.5f), Vec2(0.15f, 0.6f), Vec2(1.0f)}) {
    const Ggx g(a.x, a.y);
    SCOPED_TRACE("α = " + std::to_string(a.x) + ", " + std::to_string(a.y));
    EXPECT_TRUE(close(test::sphereQuadrature(4000, 400, [&](const Vec3& m) { return g.d(m) * std::max(0.0f, m.z); }),
                      1.0, 2e-3));
    for (const Vec3& w : knownDirections())
      EXPECT_TRUE(close(test::sphereQuadrature(4000, 400, [&](const Vec3& m) { return g.visiblePdf(w, m); }), 1.0, 2e-3))
          << "w.z = " << w.z;
  }
}

TEST(GgxDistribution, ByHand) {
  // Isotropic α: D(n) = 1/(π α²); Λ(n) = 0; Λ at θ with tan θ = 1: (√(1 + α²) − 1)/2.
  const Ggx g(0.5f, 0.5f);
  EXPECT_NEAR(g.d(Vec3(0, 0, 1)), 1.0 / (kPi * 0.25), 1e-5);
  EXPECT_EQ(g.lambda(Vec3(0, 0, 1)), 0.0f);
  const Vec3 w45 = glm::normalize(Vec3(1, 0, 1));
  EXPECT_NEAR(g.lambda(w45), 0.5 * (std::sqrt(1.25) - 1.0), 1e-6);
  EXPECT_EQ(g.lambda(w45), g.lambda(-w45)) << "the same facets seen from below";
  // Anisotropic: D along x uses α_x only. m at 45° in the xz plane: k = 1/(2α_x²) + 1/2.
  const Ggx an(0.2f, 0.8f);
  EXPECT_NEAR(an.d(w45), 1.0 / (kPi * 0.16 * sqr(0.5f / 0.04f + 0.5f)), 1e-6);
}

TEST(GgxDistribution, VisibleNormalsChi2) {
  // sampleVisible against visiblePdf over the hemisphere of normals.
  const int nCos = 20, nPhi = 24, sub = 8, n = 200000;
  uint64_t seed = 1;
  for (const Vec2 a : {Vec2(0.3f), Vec2(0.2f, 0.5f)})
    for (const Vec3& w : knownDirections()) {
      const Ggx g(a.x, a.y);
      std::vector<double> obs(size_t(nCos * nPhi), 0.0), exp(obs.size(), 0.0);
      Rng rng(seed++);
      for (int s = 0; s < n; ++s) {
        const Vec3 m = g.sampleVisible(w, Vec2(rng.uniform(), rng.uniform()));
        ASSERT_GT(m.z, 0.0f);
        ASSERT_GT(glm::dot(m, w) * w.z, 0.0f) << "a visible facet faces the viewer";
        float phi = std::atan2(m.y, m.x);
        if (phi < 0.0f) phi += 2.0f * kPi;
        obs[size_t(std::min(int(m.z * nCos), nCos - 1) * nPhi + std::min(int(phi / (2 * kPi) * nPhi), nPhi - 1))] += 1;
      }
      const double dc = 1.0 / nCos, dp = 2.0 * kPi / nPhi;
      for (int i = 0; i < nCos; ++i)
        for (int j = 0; j < nPhi; ++j)
          for (int a2 = 0; a2 < sub; ++a2)
            for (int b = 0; b < sub; ++b) {
              const Vec3 m = dirFromCosPhi(float((i + (a2 + 0.5) / sub) * dc), float((j + (b + 0.5) / sub) * dp));
              exp[size_t(i * nPhi + j)] += n * g.visiblePdf(w, m) * dc * dp / (sub * sub);
            }
      EXPECT_GT(test::chi2PValue(obs, exp), 1e-3) << "α = " << a.x << ", " << a.y << ", w.z = " << w.z;
    }
}

// ---------------------------------------------------------------------------------------------
// The conductor: sampling

TEST(RoughConductorChi2, BothModesIsotropicAndAnisotropic) {
  uint64_t seed = 10;
  for (const Vec2 a : {Vec2(0.3f), Vec2(0.15f, 0.5f)}) {
    const RoughConductor m(goldF0(), a.x, a.y);
    for (const TransportMode mode : kModes)
      for (const Vec3& w : knownDirections()) {
        const test::DirectionChi2Result r = test::directionChi2(m, mode, w, 550.0f, seed++);
        EXPECT_GT(r.p, 1e-3) << toString(mode) << " α = " << a.x << ", " << a.y << ", w.z = " << w.z;
        // Failed samples (mirrored below the surface) are exactly the missing density mass:
        // binomial at 4σ.
        const double n = test::DirectionChi2Config{}.samples, pFail = 1.0 - r.expectedMass;
        EXPECT_NEAR(r.failed, n * pFail, 4.0 * std::sqrt(n * std::max(pFail, 1e-6) * (1.0 - pFail)) + 2.0)
            << toString(mode) << " w.z = " << w.z;
      }
  }
}

TEST(RoughConductorSampling, SampleMatchesPdfEvalAndWeight) {
  const RoughConductor m(goldF0(), 0.2f, 0.4f);
  Rng rng(5);
  int checked = 0;
  for (int i = 0; i < 20000; ++i) {
    const TransportMode mode = kModes[i & 1];
    const Vec3 w = randomDirection(rng);
    const float l = 400.0f + 300.0f * rng.uniform();
    const std::optional<ScatterSample> s = m.sample(mode, w, l, Vec3(rng.uniform(), rng.uniform(), rng.uniform()));
    if (!s) continue;
    ++checked;
    EXPECT_GT(s->w.z * w.z, 0.0f);
    const double weight = test::expectConsistentSample(m, mode, w, l, *s, 1e-4);
    const auto [wi, wo] = test::physicalOrder(mode, w, s->w);
    // Weight = F(|ω·h|)·G1(ω_sampled) (rough_conductor.h).
    const Vec3 h = reflectionHalfVector(wi, wo);
    EXPECT_TRUE(close(weight, goldSchlick(std::abs(glm::dot(w, h)), l) * m.ggx().g1(s->w), 2e-4));
  }
  EXPECT_GT(checked, 15000);
}

// ---------------------------------------------------------------------------------------------
// Reciprocity and energy

TEST(RoughConductorEval, ReciprocalAndTheSameInBothModes) {
  const RoughConductor m(goldF0(), 0.1f, 0.3f);
  Rng rng(7);
  for (int i = 0; i < 5000; ++i) {
    const Vec3 a = randomDirection(rng), b = randomDirection(rng);
    const float l = 400.0f + 300.0f * rng.uniform();
    const float fab = m.eval({TransportMode::Radiance, SpectralLobe::Elastic, l, l}, a, b);
    EXPECT_TRUE(close(fab, m.eval({TransportMode::Radiance, SpectralLobe::Elastic, l, l}, b, a), 1e-5));
    EXPECT_EQ(fab, m.eval({TransportMode::Importance, SpectralLobe::Elastic, l, l}, a, b));
    if (a.z * b.z < 0.0f) {
      EXPECT_EQ(fab, 0.0f) << "no transmission";
    }
    EXPECT_EQ(m.eval({TransportMode::Radiance, SpectralLobe::Fluorescent, l, 600.0f}, a, b), 0.0f);
  }
}

// White furnace with F = 1: the directional albedo ∫ f·|cos θ_o| dω_o by quadrature equals the mean
// sampled weight (an independent Monte Carlo estimate), and is at most 1.
TEST(RoughConductorEnergy, WhiteFurnaceAlbedo) {
  uint64_t seed = 3;
  for (const Vec2 a : {Vec2(0.05f), Vec2(0.3f), Vec2(0.2f, 0.7f), Vec2(1.0f)}) {
    const RoughConductor m(Spectrum::constant(1.0f), a.x, a.y);
    for (const Vec3& w : knownDirections()) {
      // f is symmetric and the same in both modes, so one quadrature serves both.
      const double quad = test::sphereQuadrature(2000, 500, [&](const Vec3& o) {
        return double(m.eval({TransportMode::Radiance, SpectralLobe::Elastic, 500.0f, 500.0f}, w, o)) * std::abs(o.z);
      });
      for (const TransportMode mode : kModes) {
        const test::BatchStats st = test::sampledAlbedo(m, mode, w, 500.0f, seed++);
        EXPECT_LE(quad, 1.0 + 1e-3);
        EXPECT_NEAR(st.mean, quad, 4.0 * st.stderr_ + 2e-3 * quad)
            << toString(mode) << " α = " << a.x << ", " << a.y << ", w.z = " << w.z;
        // Rougher surfaces lose more to masking; at α = 1 and grazing a visible amount.
        if (a.x >= 0.3f) {
          EXPECT_LT(quad, 0.999);
        }
      }
    }
  }
}

// ---------------------------------------------------------------------------------------------
// The smooth limit

TEST(RoughConductorLimit, SmallRoughnessApproachesTheMirror) {
  // α = 0.001: samples lie within a few mrad of the mirror direction and carry the weight of a
  // smooth mirror of reflectance F(cos θ) (G1 → 1). GGX has long tails: the fraction of normals
  // with tan θ_m > t is α²/(α² + t²) (isotropic), 1% at t = 10α, so a few samples land further out.
  const RoughConductor m(goldF0(), kMinAlpha, kMinAlpha);
  Rng rng(9);
  for (const TransportMode mode : kModes)
    for (const Vec3& w : knownDirections()) {
      const Mirror mirror(Spectrum::constant(float(goldSchlick(std::abs(w.z), 550.0f))));
      const std::optional<ScatterSample> ref = mirror.sample(mode, w, 550.0f, Vec3(0.5f));
      ASSERT_TRUE(ref);
      int far = 0;
      const int n = 2000;
      for (int i = 0; i < n; ++i) {
        const std::optional<ScatterSample> s = m.sample(mode, w, 550.0f, Vec3(rng.uniform(), rng.uniform(), rng.uniform()));
        ASSERT_TRUE(s);
        if (glm::dot(s->w, specular::reflect(w)) < std::cos(0.05f)) {  // θ_m > 0.025 rad: ~0.2%
          ++far;
          continue;
        }
        const float weight = s->f * std::abs(s->w.z) / s->pdf, mirrorWeight = ref->f * std::abs(ref->w.z) / ref->pdf;
        // Schlick's F varies by |dF/dθ| ≤ 5(1 − F0)(1 − cos θ)⁴ ≈ 0.5/rad at cos θ = 0.25, over θ_m ≤ 0.025.
        EXPECT_NEAR(weight, mirrorWeight, 0.015f) << toString(mode) << " w.z = " << w.z;
      }
      EXPECT_LE(far, n / 100) << toString(mode) << " w.z = " << w.z;
    }
}

// ---------------------------------------------------------------------------------------------
// Scene-file form

std::string parseError(const nlohmann::json& v) {
  const SpectrumContext ctx{"scene.json", ".", nullptr};
  try {
    parseMaterial(v, ctx, "/materials/m", WavelengthRange{});
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

TEST(RoughConductorJson, ParsesAndRejects) {
  const SpectrumContext ctx{"scene.json", ".", nullptr};
  const auto m = parseMaterial({{"type", "rough_conductor"}, {"reflectance", 0.9}, {"alpha", {0.1, 0.3}}}, ctx,
                               "/materials/m", WavelengthRange{});
  const auto* rc = dynamic_cast<const RoughConductor*>(m.get());
  ASSERT_NE(rc, nullptr);
  EXPECT_EQ(rc->ggx().alphaX(), 0.1f);
  EXPECT_EQ(rc->ggx().alphaY(), 0.3f);
  const std::string at = "scene.json: /materials/m";
  EXPECT_EQ(parseError({{"type", "rough_conductor"}, {"reflectance", 0.9}}), at + "/alpha: missing required field");
  EXPECT_EQ(parseError({{"type", "rough_conductor"}, {"reflectance", 0.9}, {"alpha", 0.0}}),
            at + "/alpha: roughness must lie in [0.001, 1]");
  EXPECT_EQ(parseError({{"type", "rough_conductor"}, {"reflectance", 0.9}, {"alpha", {0.1}}}),
            at + "/alpha: expected a roughness or an array [alpha_x, alpha_y], got array");
  EXPECT_EQ(parseError({{"type", "rough_conductor"}, {"reflectance", 1.2}, {"alpha", 0.2}}),
            at + "/reflectance: reflectance 1.200000 exceeds 1 in the wavelength range");
}

}  // namespace
}  // namespace kasha
