// Unit tests of the rough dielectric (materials/rough_dielectric.h): docs/validation.md §3 for glossy
// reflection and refraction, both transport modes, Veach's η² relation, and the smooth limit
// against materials/dielectric.h.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "core/error.h"
#include "core/rng.h"
#include "materials/dielectric.h"
#include "materials/fresnel.h"
#include "materials/material_json.h"
#include "materials/rough_dielectric.h"
#include "tests/glossy_support.h"
#include "tests/material_support.h"
#include "tests/support.h"

namespace kasha {
namespace {

using test::close;
using test::dirFromCosPhi;
using test::randomDirection;

const WavelengthRange kRange{360.0f, 830.0f};
const TransportMode kModes[] = {TransportMode::Radiance, TransportMode::Importance};

// Known directions on both sides; from inside, cos θ = 0.25 is beyond the critical angle of the
// smooth surface (sin θ = 0.97 > 1/1.5), where only rough facets let light out.
std::vector<Vec3> knownDirections() {
  std::vector<Vec3> ws;
  for (const float c : {0.95f, 0.6f, 0.25f})
    for (const float side : {1.0f, -1.0f}) ws.push_back(dirFromCosPhi(side * c, 0.4f + 2.0f * c));
  return ws;
}

double weight(const ScatterSample& s) { return s.f * std::abs(s.w.z) / s.pdf; }

// ---------------------------------------------------------------------------------------------
// Sampling

TEST(RoughDielectricChi2, BothModesBothSides) {
  uint64_t seed = 20;
  for (const Vec2 a : {Vec2(0.3f), Vec2(0.2f, 0.5f)}) {
    const RoughDielectric m(*Ior::preset("BK7"), a.x, a.y, kRange);
    for (const TransportMode mode : kModes)
      for (const Vec3& w : knownDirections()) {
        // Refraction from outside concentrates the lobe around the pole, where cells in cos θ are
        // wide in θ: a fine sub-grid keeps the expected counts accurate.
        test::DirectionChi2Config cfg;
        cfg.sub = 24;
        const test::DirectionChi2Result r = test::directionChi2(m, mode, w, 550.0f, seed++, cfg);
        EXPECT_GT(r.p, 1e-3) << toString(mode) << " α = " << a.x << ", " << a.y << ", w.z = " << w.z;
        // Failed samples are the missing density mass: binomial at 4σ, plus 0.1% of n for the
        // quadrature error of that mass.
        const double n = cfg.samples, pFail = 1.0 - r.expectedMass;
        EXPECT_NEAR(r.failed, n * pFail, 4.0 * std::sqrt(n * std::max(pFail, 1e-6) * (1.0 - pFail)) + 1e-3 * n)
            << toString(mode) << " w.z = " << w.z;
      }
  }
}

TEST(RoughDielectricSampling, SampleMatchesPdfEvalAndWeight) {
  const RoughDielectric m(*Ior::preset("BK7"), 0.25f, 0.4f, kRange);
  Rng rng(5);
  int reflected = 0, refracted = 0;
  for (int i = 0; i < 40000; ++i) {
    const TransportMode mode = kModes[i & 1];
    const Vec3 w = randomDirection(rng);
    const float l = 400.0f + 300.0f * rng.uniform();
    const std::optional<ScatterSample> s = m.sample(mode, w, l, Vec3(rng.uniform(), rng.uniform(), rng.uniform()));
    if (!s) continue;
    const double w8 = test::expectConsistentSample(m, mode, w, l, *s, 1e-3);
    const auto [wi, wo] = test::physicalOrder(mode, w, s->w);
    // The weights of rough_dielectric.h, with F at the facet the two directions define.
    const bool reflect = s->w.z * w.z > 0.0f;
    const float etaI = m.sideIndex(wi, l), etaO = m.sideIndex(wo, l);
    const Vec3 h = reflect ? reflectionHalfVector(wi, wo) : refractionHalfVector(wi, etaI, wo, etaO);
    const float F = fresnelDielectric(std::abs(glm::dot(w, h)), m.sideIndex(-w, l) / m.sideIndex(w, l));
    const float pr = m.reflectProbability(w, l);
    double expect = reflect ? F / pr : (1.0f - F) / (1.0f - pr);
    if (!reflect && mode == TransportMode::Radiance) expect *= sqr(etaO / etaI);
    expect *= m.ggx().g1(s->w);
    EXPECT_TRUE(close(w8, expect, 2e-3, 1e-6)) << toString(mode) << (reflect ? " reflect" : " refract");
    ++(reflect ? reflected : refracted);
  }
  EXPECT_GT(reflected, 5000);
  EXPECT_GT(refracted, 10000);
}

// ---------------------------------------------------------------------------------------------
// Transport modes and reciprocity

TEST(RoughDielectricEval, VeachRelationAndOneValueForBothModes) {
  // Veach97 §5.2: f(a→b)/η_b² = f(b→a)/η_a²; reflection is plainly symmetric.
  const RoughDielectric m(*Ior::preset("BK7"), 0.2f, 0.35f, kRange);
  Rng rng(8);
  int transmitted = 0;
  for (int i = 0; i < 20000; ++i) {
    const Vec3 a = randomDirection(rng), b = randomDirection(rng);
    const float l = 400.0f + 300.0f * rng.uniform();
    const float fab = m.eval({TransportMode::Radiance, SpectralLobe::Elastic, l, l}, a, b);
    const float fba = m.eval({TransportMode::Radiance, SpectralLobe::Elastic, l, l}, b, a);
    EXPECT_EQ(fab, m.eval({TransportMode::Importance, SpectralLobe::Elastic, l, l}, a, b));
    EXPECT_TRUE(close(fab / sqr(m.sideIndex(b, l)), fba / sqr(m.sideIndex(a, l)), 1e-4, 1e-12));
    transmitted += a.z * b.z < 0.0f && fab > 0.0f;
    EXPECT_EQ(m.eval({TransportMode::Radiance, SpectralLobe::Fluorescent, l, 600.0f}, a, b), 0.0f);
  }
  EXPECT_GT(transmitted, 1000);
  // By hand at normal incidence on n = 1.5, through the facet m = z: h_t = z, F = 0.04, G1 = 1,
  // D = 1/(πα²): f = 1·1/(1·1)·1.5²·0.96·D / (1·1 − 1.5·1)² ... with ω_i = z, ω_o = −z the
  // denominator is (η_i(ω_i·h) + η_o(ω_o·h))² = (1 − 1.5)² = 0.25.
  const RoughDielectric g(Ior::constant(1.5), 0.3f, 0.3f, kRange);
  const double D = 1.0 / (kPi * 0.09);
  EXPECT_TRUE(
      close(g.eval({TransportMode::Radiance, SpectralLobe::Elastic, 500.0f, 500.0f}, Vec3(0, 0, 1), Vec3(0, 0, -1)),
            2.25 * 0.96 * D / 0.25, 1e-5));
  EXPECT_TRUE(
      close(g.eval({TransportMode::Radiance, SpectralLobe::Elastic, 500.0f, 500.0f}, Vec3(0, 0, -1), Vec3(0, 0, 1)),
            1.0 * 0.96 * D / 0.25, 1e-5));
}

// ---------------------------------------------------------------------------------------------
// Energy: the albedo by quadrature of f equals the mean sampled weight, in both modes; in
// Importance mode (power) it is at most 1.

TEST(RoughDielectricEnergy, AlbedoByQuadratureEqualsSampledWeight) {
  uint64_t seed = 40;
  for (const Vec2 a : {Vec2(0.3f), Vec2(0.15f, 0.6f)}) {
    const RoughDielectric m(Ior::constant(1.5), a.x, a.y, kRange);
    for (const Vec3& w : knownDirections())
      for (const TransportMode mode : kModes) {
        const double quad = test::sphereQuadrature(2000, 500, [&](const Vec3& o) {
          const auto [wi, wo] = test::physicalOrder(mode, w, o);
          return double(m.eval({mode, SpectralLobe::Elastic, 500.0f, 500.0f}, wi, wo)) * std::abs(o.z);
        });
        const test::BatchStats st = test::sampledAlbedo(m, mode, w, 500.0f, seed++);
        EXPECT_NEAR(st.mean, quad, 4.0 * st.stderr_ + 3e-3 * quad)
            << toString(mode) << " α = " << a.x << ", " << a.y << ", w.z = " << w.z;
        if (mode == TransportMode::Importance) {
          EXPECT_LE(quad, 1.0 + 1e-3) << "w.z = " << w.z;
        }
      }
  }
}

// ---------------------------------------------------------------------------------------------
// The smooth limit: at α = 0.001 the reflected and refracted energies are the smooth Fresnel
// ones (times (η_o/η_i)² for refraction in Radiance mode), and the directions the smooth ones.

TEST(RoughDielectricLimit, SmallRoughnessApproachesTheSmoothDielectric) {
  const RoughDielectric m(*Ior::preset("BK7"), kMinAlpha, kMinAlpha, kRange);
  const Dielectric smooth(*Ior::preset("BK7"), kRange);
  uint64_t seed = 60;
  for (const TransportMode mode : kModes)
    for (const Vec3& w : knownDirections()) {
      const float l = 500.0f;
      // The smooth material's two outcomes and their expected weights.
      double smoothR = 0.0, smoothT = 0.0;
      Vec3 dirR(0.0f), dirT(0.0f);
      for (const float u : {0.0f, 0.999999f})
        if (auto s = smooth.sample(mode, w, l, Vec3(0.5f, u, 0.5f))) {
          const bool refl = s->w.z * w.z > 0.0f;
          (refl ? smoothR : smoothT) = s->pdf * weight(*s);
          (refl ? dirR : dirT) = s->w;
        }
      Rng rng(seed++);
      const int n = 20000;
      std::vector<double> sumR(10, 0.0), sumT(10, 0.0);
      int far = 0;
      for (int k = 0; k < n; ++k) {
        const std::optional<ScatterSample> s = m.sample(mode, w, l, Vec3(rng.uniform(), rng.uniform(), rng.uniform()));
        if (!s) continue;
        const bool refl = s->w.z * w.z > 0.0f;
        far += glm::dot(s->w, refl ? dirR : dirT) < std::cos(0.05f);
        (refl ? sumR : sumT)[size_t(k % 10)] += weight(*s) / (n / 10);
      }
      const test::BatchStats r = test::batchStats(sumR), t = test::batchStats(sumT);
      // Tolerance: 4σ plus GGX's tail (normals beyond a few α change F) and G1 < 1: 1%.
      EXPECT_NEAR(r.mean, smoothR, 4.0 * r.stderr_ + 0.01) << toString(mode) << " w.z = " << w.z;
      EXPECT_NEAR(t.mean, smoothT, 4.0 * t.stderr_ + 0.01 * std::max(1.0, smoothT)) << toString(mode) << " w.z = " << w.z;
      EXPECT_LE(far, n / 100) << toString(mode) << " w.z = " << w.z;
    }
}

// ---------------------------------------------------------------------------------------------
// Scene-file form

std::string parseError(const nlohmann::json& v) {
  const SpectrumContext ctx{"scene.json", ".", nullptr};
  try {
    parseMaterial(v, ctx, "/materials/m", kRange);
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

TEST(RoughDielectricJson, ParsesAndRejects) {
  const SpectrumContext ctx{"scene.json", ".", nullptr};
  const auto m = parseMaterial({{"type", "rough_dielectric"}, {"ior", "BK7"}, {"alpha", 0.2}}, ctx, "/materials/m", kRange);
  const auto* rd = dynamic_cast<const RoughDielectric*>(m.get());
  ASSERT_NE(rd, nullptr);
  EXPECT_EQ(rd->ggx().alphaX(), 0.2f);
  EXPECT_EQ(rd->ggx().alphaY(), 0.2f);
  EXPECT_NEAR(rd->ior()(587.5618f), 1.5168f, 1e-4f);
  const std::string at = "scene.json: /materials/m";
  EXPECT_EQ(parseError({{"type", "rough_dielectric"}, {"ior", 1.0}, {"alpha", 0.2}}),
            at + "/ior: index of refraction 1.000000 at 360.000000 nm is within 0.001 of 1 (a rough surface needs an "
                 "index contrast)");
  EXPECT_EQ(parseError({{"type", "rough_dielectric"}, {"ior", 0.8}, {"alpha", 0.2}}),
            at + "/ior: index of refraction 0.800000 is below 1");
  EXPECT_EQ(parseError({{"type", "rough_dielectric"}, {"ior", 1.5}, {"alpha", {0.2, 2.0}}}),
            at + "/alpha: roughness must lie in [0.001, 1]");
  EXPECT_EQ(parseError({{"type", "rough_dielectric"}, {"ior", 1.5}, {"alpha", "rough"}}),
            at + "/alpha: expected a roughness or an array [alpha_x, alpha_y], got string");
}

}  // namespace
}  // namespace kasha
