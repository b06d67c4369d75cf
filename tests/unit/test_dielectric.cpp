// Unit tests of the smooth dielectric (materials/dielectric.h, fresnel.h, specular_lobe.h):
// docs/validation.md §3 for two specular elastic lobes. Fresnel is checked against Fresnel's
// trigonometric form of the same equations, the discrete sampling against F by a binomial test,
// and the transport-mode factor against Veach's relations for refraction (Veach97 §5.2).
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "core/error.h"
#include "core/rng.h"
#include "materials/dielectric.h"
#include "materials/fresnel.h"
#include "materials/material_json.h"
#include "materials/specular_lobe.h"
#include "tests/material_support.h"

namespace kasha {
namespace {

using test::close;
using test::dirFromCosPhi;
using test::randomDirection;

const WavelengthRange kRange{360.0f, 830.0f};
const TransportMode kModes[] = {TransportMode::Radiance, TransportMode::Importance};

Dielectric bk7() { return Dielectric(*Ior::preset("BK7"), kRange); }

// Index on the side of direction w: vacuum outside (z > 0), n(λ) inside.
float sideIndex(const Dielectric& m, const Vec3& w, float lambda) { return w.z > 0.0f ? 1.0f : m.ior()(lambda); }

// Physical order of an event sampled in `mode` from the known direction.
struct Event {
  Vec3 wi, wo;
};
Event physical(TransportMode mode, const Vec3& wKnown, const Vec3& wSampled) {
  return mode == TransportMode::Radiance ? Event{wSampled, wKnown} : Event{wKnown, wSampled};
}

// Both outcomes from wKnown at λ (the refracted one absent under total internal reflection).
std::vector<Vec3> outcomes(const Dielectric& m, const Vec3& wKnown, float lambda) {
  std::vector<Vec3> out = {specular::reflect(wKnown)};
  if (auto t = specular::refract(wKnown, m.relativeEta(wKnown, lambda))) out.push_back(*t);
  return out;
}

// Known directions on both sides, from near-normal to grazing, including some beyond the
// critical angle seen from inside (sin θ > 1/n ≈ 0.66).
std::vector<Vec3> knownDirections() {
  std::vector<Vec3> ws;
  for (const float c : {0.99f, 0.8f, 0.5f, 0.2f, 0.05f})
    for (const float side : {1.0f, -1.0f}) ws.push_back(dirFromCosPhi(side * c, 0.7f + 2.0f * c));
  return ws;
}

// ---------------------------------------------------------------------------------------------
// Fresnel

// Fresnel's sine and tangent laws (Born & Wolf §1.5.2), an independent form of the same physics.
double fresnelTrig(double thetaI, double eta) {
  const double sinT = std::sin(thetaI) / eta;
  if (sinT >= 1.0) return 1.0;
  const double thetaT = std::asin(sinT);
  const double rs = -std::sin(thetaI - thetaT) / std::sin(thetaI + thetaT);
  const double rp = std::tan(thetaI - thetaT) / std::tan(thetaI + thetaT);
  return 0.5 * (rs * rs + rp * rp);
}

TEST(Fresnel, MatchesTrigonometricFormFromBothSides) {
  for (const double n : {1.33, 1.5, 2.4})
    for (const double eta : {n, 1.0 / n})
      for (double deg = 1.0; deg < 89.5; deg += 2.0) {
        const double th = deg * kPi / 180.0;
        EXPECT_NEAR(fresnelDielectric(float(std::cos(th)), float(eta)), fresnelTrig(th, eta), 2e-6)
            << "η = " << eta << ", θ = " << deg;
      }
}

TEST(Fresnel, NormalIncidenceBrewsterAndCriticalAngles) {
  const float n = 1.5f;
  // ((n − 1)/(n + 1))² = 0.04 from either side.
  EXPECT_NEAR(fresnelDielectric(1.0f, n), 0.04f, 1e-7);
  EXPECT_NEAR(fresnelDielectric(1.0f, 1.0f / n), 0.04f, 1e-7);
  // At Brewster's angle tan θ_B = n: θ_B + θ_t = 90°, so r_p = 0 and r_s = cos 2θ_B = (1 − n²)/(1 + n²).
  const float cosB = 1.0f / std::sqrt(1.0f + n * n);
  EXPECT_NEAR(fresnelDielectric(cosB, n), 0.5f * sqr((n * n - 1.0f) / (n * n + 1.0f)), 1e-6);
  // From inside: total reflection beyond the critical angle sin θ_c = 1/n, partial just before it.
  const float sinC = 1.0f / n;
  EXPECT_EQ(fresnelDielectric(std::sqrt(1.0f - sqr(sinC * 1.001f)), 1.0f / n), 1.0f);
  EXPECT_LT(fresnelDielectric(std::sqrt(1.0f - sqr(sinC * 0.99f)), 1.0f / n), 1.0f);
  // Grazing: everything reflected. Index matched: nothing.
  EXPECT_EQ(fresnelDielectric(0.0f, n), 1.0f);
  EXPECT_EQ(fresnelDielectric(0.6f, 1.0f), 0.0f);
}

// Seen from the other side, an event is known only to float rounding, which grazing refraction
// (near the critical angle) amplifies: cos θ_t = √(1 − sin²θ_t) loses digits as it goes to 0. So
// quantities compared across the two sides get a tolerance that grows as 1/cos² of the grazing
// direction.
double crossSideTolerance(const Vec3& a, const Vec3& b) {
  return 2e-7 / sqr(std::min(std::abs(a.z), std::abs(b.z)));
}

TEST(Fresnel, SameFromBothSidesOfOneEvent) {
  // F(θ_i, η) = F(θ_t, 1/η): the reflect/refract probabilities of a path and its reverse agree.
  Rng rng(8);
  for (int i = 0; i < 1000; ++i) {
    const Vec3 w = randomDirection(rng);
    const float eta = 1.0f + rng.uniform();
    const std::optional<Vec3> t = specular::refract(w, w.z > 0 ? eta : 1.0f / eta);
    if (!t) continue;
    EXPECT_NEAR(fresnelDielectric(std::abs(w.z), w.z > 0 ? eta : 1.0f / eta),
                fresnelDielectric(std::abs(t->z), t->z > 0 ? eta : 1.0f / eta), 2e-6 + crossSideTolerance(w, *t));
  }
}

// ---------------------------------------------------------------------------------------------
// Directions

TEST(DielectricSampling, SnellsLawAndSides) {
  const Dielectric m = bk7();
  Rng rng(11);
  int refracted = 0;
  for (int i = 0; i < 20000; ++i) {
    const TransportMode mode = kModes[i & 1];
    const Vec3 w = randomDirection(rng);
    const float l = kRange.min + rng.uniform() * kRange.width();
    const float F = fresnelDielectric(std::abs(w.z), m.relativeEta(w, l));
    const std::optional<DirectionSample> ds =
        m.sampleDirection({mode, SpectralLobe::Elastic, l, l}, w, Vec2(rng.uniform(), rng.uniform()));
    ASSERT_TRUE(ds);
    EXPECT_TRUE(ds->specular);
    EXPECT_NEAR(glm::length(ds->w), 1.0f, 1e-6f);
    if (ds->w.z * w.z > 0.0f) {
      EXPECT_EQ(ds->w, Vec3(-w.x, -w.y, w.z));
      EXPECT_EQ(ds->pdf, F);
      continue;
    }
    ++refracted;
    EXPECT_EQ(ds->pdf, 1.0f - F);
    // n_1·sin θ_1 = n_2·sin θ_2, and the tangential direction is reversed (plane of incidence kept).
    const float sin1 = std::sqrt(w.x * w.x + w.y * w.y), sin2 = std::sqrt(ds->w.x * ds->w.x + ds->w.y * ds->w.y);
    EXPECT_NEAR(sideIndex(m, w, l) * sin1, sideIndex(m, ds->w, l) * sin2, 2e-6);
    EXPECT_NEAR(w.x * ds->w.y - w.y * ds->w.x, 0.0f, 1e-6f);
    EXPECT_LE(w.x * ds->w.x + w.y * ds->w.y, 0.0f);
  }
  EXPECT_GT(refracted, 10000);
}

TEST(DielectricSampling, TotalInternalReflection) {
  const Dielectric m(Ior::constant(1.5), kRange);
  const float sinC = 1.0f / 1.5f;
  for (const float s : {sinC * 1.0001f, 0.8f, 0.99f}) {
    const Vec3 inside = glm::normalize(Vec3(s, 0.0f, -std::sqrt(1.0f - s * s)));
    EXPECT_FALSE(specular::refract(inside, m.relativeEta(inside, 500.0f)));
    for (const TransportMode mode : kModes)
      for (float u = 0.0f; u < 1.0f; u += 0.01f) {
        const std::optional<DirectionSample> ds =
            m.sampleDirection({mode, SpectralLobe::Elastic, 500.0f, 500.0f}, inside, Vec2(u, 0.5f));
        ASSERT_TRUE(ds);
        EXPECT_EQ(ds->w, specular::reflect(inside));
        EXPECT_EQ(ds->pdf, 1.0f);
      }
    // Nothing leaves into the outside: no value and no density for any upward direction.
    const Vec3 out = dirFromCosPhi(std::sqrt(1.0f - sqr(1.5f * s * 0.5f)), kPi);
    EXPECT_EQ(m.eval({TransportMode::Radiance, SpectralLobe::Elastic, 500.0f, 500.0f}, out, inside), 0.0f);
    EXPECT_EQ(m.directionPdf({TransportMode::Importance, SpectralLobe::Elastic, 500.0f, 500.0f}, inside, out), 0.0f);
  }
  // Just inside the critical angle the light still gets out.
  const float s = sinC * 0.999f;
  const Vec3 inside(s, 0.0f, -std::sqrt(1.0f - s * s));
  const std::optional<Vec3> t = specular::refract(inside, m.relativeEta(inside, 500.0f));
  ASSERT_TRUE(t);
  EXPECT_GT(t->z, 0.0f);
  EXPECT_LT(t->z, 0.1f);  // grazing
}

// The fraction of reflections matches F: a binomial test at 4 standard errors.
TEST(DielectricSampling, ReflectFractionIsFresnel) {
  const Dielectric m = bk7();
  const int n = 20000;
  uint64_t seed = 1;
  for (const TransportMode mode : kModes)
    for (const Vec3& w : knownDirections())
      for (const float l : {400.0f, 650.0f}) {
        const double F = fresnelDielectric(std::abs(w.z), m.relativeEta(w, l));
        Rng rng(seed++, 5);
        int reflected = 0;
        for (int i = 0; i < n; ++i) {
          const std::optional<ScatterSample> s = m.sample(mode, w, l, Vec3(rng.uniform(), rng.uniform(), rng.uniform()));
          ASSERT_TRUE(s);
          ASSERT_EQ(s->lobe, SpectralLobe::Elastic);
          ASSERT_EQ(s->lambda, l);
          if (s->w.z * w.z > 0.0f) ++reflected;
        }
        const double sigma = std::sqrt(n * F * (1.0 - F));
        EXPECT_NEAR(reflected, n * F, 4.0 * sigma + 1.0)
            << toString(mode) << " cos θ = " << w.z << " λ = " << l << ": F = " << F;
      }
}

TEST(DielectricSampling, SampleMatchesPdfBothWays) {
  const Dielectric m = bk7();
  Rng rng(21);
  for (int i = 0; i < 20000; ++i) {
    const TransportMode mode = kModes[i & 1];
    const Vec3 w = randomDirection(rng);
    const float l = kRange.min + rng.uniform() * kRange.width();
    const std::optional<ScatterSample> s = m.sample(mode, w, l, Vec3(rng.uniform(), rng.uniform(), rng.uniform()));
    ASSERT_TRUE(s);
    EXPECT_TRUE(s->specular);
    const Event ev = physical(mode, w, s->w);
    const ScatterDensity d = m.pdf({mode, SpectralLobe::Elastic, l, l}, ev.wi, ev.wo);
    EXPECT_EQ(s->pdf, d.pdf);
    EXPECT_EQ(s->pdfRev, d.pdfRev);
    EXPECT_TRUE(close(s->f, m.eval({mode, SpectralLobe::Elastic, l, l}, ev.wi, ev.wo), 1e-6));
    // The reverse density is the forward density of the other mode, and (F being the same from both
    // sides) equal to the forward one.
    EXPECT_EQ(d.pdfRev, m.pdf({flip(mode), SpectralLobe::Elastic, l, l}, ev.wi, ev.wo).pdf);
    EXPECT_NEAR(s->pdfRev, s->pdf, 2e-6 + crossSideTolerance(w, s->w));
  }
}

TEST(DielectricSampling, DiscreteProbabilitiesSumToOne) {
  const Dielectric m = bk7();
  for (const TransportMode mode : kModes)
    for (const Vec3& w : knownDirections())
      for (const float l : {380.0f, 550.0f, 820.0f}) {
        double total = 0.0;
        for (const Vec3& o : outcomes(m, w, l)) total += m.directionPdf({mode, SpectralLobe::Elastic, l, l}, w, o);
        EXPECT_NEAR(total, 1.0, 1e-6) << toString(mode) << " cos θ = " << w.z;
        // Spectral stage: elastic with probability 1, no fluorescent lobe.
        EXPECT_EQ(m.spectralPdf(mode, l, l, SpectralLobe::Elastic), 1.0f);
        EXPECT_EQ(m.spectralPdf(mode, l, 600.0f, SpectralLobe::Fluorescent), 0.0f);
        EXPECT_EQ(m.eval({mode, SpectralLobe::Fluorescent, l, l}, w, outcomes(m, w, l).back()), 0.0f);
      }
}

TEST(DielectricEval, NothingOffTheTwoDirections) {
  const Dielectric m = bk7();
  Rng rng(2);
  for (int i = 0; i < 5000; ++i) {
    const Vec3 w = randomDirection(rng), other = randomDirection(rng);
    const float l = kRange.min + rng.uniform() * kRange.width();
    bool nearLobe = false;
    for (const Vec3& o : outcomes(m, w, l)) nearLobe |= glm::dot(o, other) > 0.999f;
    if (nearLobe) continue;
    for (const TransportMode mode : kModes) {
      const Event ev = physical(mode, w, other);
      EXPECT_EQ(m.eval({mode, SpectralLobe::Elastic, l, l}, ev.wi, ev.wo), 0.0f);
      EXPECT_EQ(m.pdf({mode, SpectralLobe::Elastic, l, l}, ev.wi, ev.wo).pdf, 0.0f);
    }
  }
}

// ---------------------------------------------------------------------------------------------
// Transport modes: energy, the η² factor and Veach's relations

TEST(DielectricModes, ImportanceCarriesPowerRPlusTIsOne) {
  // A particle's power splits into R + T = 1: Σ over both outcomes of f·|cos θ_o| is 1, and every
  // sampled weight f·|cos θ_o|/pdf is exactly 1.
  const Dielectric m = bk7();
  for (const Vec3& wi : knownDirections())
    for (const float l : {400.0f, 550.0f, 700.0f}) {
      double power = 0.0;
      for (const Vec3& wo : outcomes(m, wi, l)) {
        const float f = m.eval({TransportMode::Importance, SpectralLobe::Elastic, l, l}, wi, wo);
        const float p = m.directionPdf({TransportMode::Importance, SpectralLobe::Elastic, l, l}, wi, wo);
        power += f * std::abs(wo.z);
        if (p > 0.0f) EXPECT_NEAR(f * std::abs(wo.z) / p, 1.0f, 1e-5f);
      }
      EXPECT_NEAR(power, 1.0, 1e-6) << "cos θ_i = " << wi.z << ", λ = " << l;
    }
}

TEST(DielectricModes, RadianceRefractionScalesByEtaSquared) {
  const Dielectric m = bk7();
  Rng rng(17);
  for (int i = 0; i < 5000; ++i) {
    const Vec3 wo = randomDirection(rng);
    const float l = kRange.min + rng.uniform() * kRange.width();
    const std::optional<Vec3> wi = specular::refract(wo, m.relativeEta(wo, l));
    if (!wi) continue;
    const float etaI = sideIndex(m, *wi, l), etaO = sideIndex(m, wo, l);
    // The same physical event (light from ω_i to ω_o) seen from either end: the path weights
    // f·|cos θ_sampled| differ by exactly (η_o/η_i)².
    const float fR = m.eval({TransportMode::Radiance, SpectralLobe::Elastic, l, l}, *wi, wo);
    const float fI = m.eval({TransportMode::Importance, SpectralLobe::Elastic, l, l}, *wi, wo);
    EXPECT_NEAR(fR * std::abs(wi->z), sqr(etaO / etaI) * fI * std::abs(wo.z),
                sqr(etaO / etaI) * (2e-6 + crossSideTolerance(wo, *wi)));
    // Radiance weight = (η_o/η_i)²·T.
    const float T = 1.0f - fresnelDielectric(std::abs(wo.z), m.relativeEta(wo, l));
    EXPECT_TRUE(close(fR * std::abs(wi->z), sqr(etaO / etaI) * T, 2e-5));
  }
  // The direction of the factor, by hand at normal incidence on n = 1.5 (T = 0.96): radiance
  // entering the glass is compressed into a smaller solid angle and grows, 0.96·1.5² = 2.16;
  // radiance leaving it shrinks, 0.96/1.5².
  const Dielectric g(Ior::constant(1.5), kRange);
  const Vec3 up(0, 0, 1), down(0, 0, -1);
  EXPECT_NEAR(g.eval({TransportMode::Radiance, SpectralLobe::Elastic, 500.0f, 500.0f}, up, down), 2.16f, 1e-5f);
  EXPECT_NEAR(g.eval({TransportMode::Radiance, SpectralLobe::Elastic, 500.0f, 500.0f}, down, up), 0.96f / 2.25f, 1e-6f);
  EXPECT_NEAR(g.eval({TransportMode::Importance, SpectralLobe::Elastic, 500.0f, 500.0f}, up, down), 0.96f, 1e-6f);
  EXPECT_NEAR(g.eval({TransportMode::Importance, SpectralLobe::Elastic, 500.0f, 500.0f}, down, up), 0.96f, 1e-6f);
}

TEST(DielectricModes, VeachRelationForRefraction) {
  // Veach97 §5.2: f(ω_a→ω_b)/η_b² = f(ω_b→ω_a)/η_a², both deltas taken in ω_a's solid angle:
  // on the left ω_a is the incident direction (sampled in Radiance mode), on the right the exitant
  // one (sampled in Importance mode). Reflection is symmetric.
  const Dielectric m = bk7();
  Rng rng(29);
  for (int i = 0; i < 5000; ++i) {
    const Vec3 b = randomDirection(rng);
    const float l = kRange.min + rng.uniform() * kRange.width();
    for (const Vec3& a : outcomes(m, b, l)) {
      const float fAB = m.eval({TransportMode::Radiance, SpectralLobe::Elastic, l, l}, a, b);
      const float fBA = m.eval({TransportMode::Importance, SpectralLobe::Elastic, l, l}, b, a);
      EXPECT_TRUE(close(fAB / sqr(sideIndex(m, b, l)), fBA / sqr(sideIndex(m, a, l)), 2e-5));
    }
  }
}

TEST(DielectricModes, UniformFieldIsInvariant) {
  // A uniform isotropic field in equilibrium has radiance L outside and n²·L inside (basic
  // radiance L/n² is conserved). One Radiance-mode scattering step must reproduce it exactly:
  // Σ_k pdf_k·weight_k·L(ω_i,k) = L(ω_o). A factor in the wrong mode or direction breaks it.
  const Dielectric m = bk7();
  for (const Vec3& wo : knownDirections())
    for (const float l : {400.0f, 550.0f, 700.0f}) {
      const auto field = [&](const Vec3& w) { return sqr(sideIndex(m, w, l)); };
      double gathered = 0.0;
      for (const Vec3& wi : outcomes(m, wo, l))
        gathered += m.eval({TransportMode::Radiance, SpectralLobe::Elastic, l, l}, wi, wo) * std::abs(wi.z) * field(wi);
      EXPECT_NEAR(gathered, field(wo), 1e-5 * field(wo)) << "cos θ_o = " << wo.z << ", λ = " << l;
    }
}

// ---------------------------------------------------------------------------------------------
// Dispersion

TEST(DielectricDispersion, EachWavelengthRefractsIntoItsOwnDirection) {
  const Dielectric m = bk7();
  const Vec3 w = dirFromCosPhi(std::cos(45.0f * kPi / 180.0f), 0.3f);
  // Refraction is the second outcome: u.x = 0.99 > F ≈ 0.05.
  const auto refracted = [&](float l) {
    const std::optional<ScatterSample> s = m.sample(TransportMode::Radiance, w, l, Vec3(0.5f, 0.99f, 0.5f));
    EXPECT_TRUE(s && s->w.z < 0.0f);
    return s->w;
  };
  const Vec3 blue = refracted(400.0f), red = refracted(700.0f);
  // Snell with n(400) = 1.5308 and n(700) = 1.5131: θ_t = 27.49° and 27.85°, 6.2 mrad apart.
  const float expected = std::asin(std::sin(kPi / 4.0f) / m.ior()(700.0f)) - std::asin(std::sin(kPi / 4.0f) / m.ior()(400.0f));
  EXPECT_NEAR(expected, 6.2e-3f, 0.2e-3f);
  EXPECT_NEAR(std::acos(std::clamp(glm::dot(blue, red), -1.0f, 1.0f)), expected, 0.2e-3f);
  EXPECT_GT(std::abs(blue.z), std::abs(red.z)) << "blue bends more, towards the normal";
  // The red lobe does not contain the blue direction, and vice versa.
  EXPECT_EQ(m.eval({TransportMode::Radiance, SpectralLobe::Elastic, 700.0f, 700.0f}, blue, w), 0.0f);
  EXPECT_EQ(m.eval({TransportMode::Radiance, SpectralLobe::Elastic, 400.0f, 400.0f}, red, w), 0.0f);
  EXPECT_GT(m.eval({TransportMode::Radiance, SpectralLobe::Elastic, 400.0f, 400.0f}, blue, w), 0.0f);
  EXPECT_EQ(m.directionPdf({TransportMode::Radiance, SpectralLobe::Elastic, 700.0f, 700.0f}, w, blue), 0.0f);
  // A constant index does not disperse.
  const Dielectric flat(Ior::constant(1.5), kRange);
  EXPECT_EQ(flat.sample(TransportMode::Radiance, w, 400.0f, Vec3(0.5f, 0.99f, 0.5f))->w,
            flat.sample(TransportMode::Radiance, w, 700.0f, Vec3(0.5f, 0.99f, 0.5f))->w);
}

// ---------------------------------------------------------------------------------------------
// Scene-file form

std::unique_ptr<Material> parse(const nlohmann::json& ior) {
  const SpectrumContext ctx{"scene.json", ".", nullptr};
  return parseMaterial({{"type", "dielectric"}, {"ior", ior}}, ctx, "/materials/g", kRange);
}

std::string parseError(const nlohmann::json& ior) {
  try {
    parse(ior);
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

float indexAt(const nlohmann::json& ior, float l) {
  const std::unique_ptr<Material> m = parse(ior);
  const auto* d = dynamic_cast<const Dielectric*>(m.get());
  EXPECT_NE(d, nullptr);
  return d ? d->ior()(l) : 0.0f;
}

TEST(DielectricJson, EveryIndexForm) {
  EXPECT_FLOAT_EQ(indexAt(1.33, 500.0f), 1.33f);
  EXPECT_NEAR(indexAt("BK7", 587.5618f), 1.5168f, 1e-4f);
  EXPECT_NEAR(indexAt("fused_silica", 587.5618f), 1.4585f, 1e-4f);
  EXPECT_NEAR(indexAt({{"type", "cauchy"}, {"A", 1.5}, {"B", 0.004}}, 500.0f), 1.516f, 1e-6f);
  EXPECT_NEAR(indexAt({{"type", "cauchy"}, {"A", 1.5}, {"B", 0.004}, {"C", 1e-4}}, 500.0f), 1.5176f, 1e-6f);
  const nlohmann::json bk7 = {{"type", "sellmeier"},
                              {"B", {1.03961212, 0.231792344, 1.01046945}},
                              {"C", {0.00600069867, 0.0200179144, 103.560653}}};
  EXPECT_NEAR(indexAt(bk7, 587.5618f), 1.5168f, 1e-4f);
  EXPECT_EQ(parse("BK7")->describe().rfind("dielectric (Sellmeier", 0), 0u);
}

TEST(DielectricJson, ClearErrors) {
  const std::string at = "scene.json: /materials/g/ior";
  EXPECT_EQ(parseError(0.9), at + ": index of refraction 0.900000 is below 1");
  EXPECT_EQ(parseError(1e39), at + ": index of refraction is not a finite real number");
  EXPECT_EQ(parseError("diamond"), at + ": unknown index of refraction preset 'diamond' (BK7, fused_silica)");
  EXPECT_EQ(parseError("NaN"), at + ": unknown index of refraction preset 'NaN' (BK7, fused_silica)");
  EXPECT_EQ(parseError(nlohmann::json::array({1.5})), at + ": expected a number, a preset name or an object, got array");
  EXPECT_EQ(parseError({{"type", "abbe"}}), at + "/type: unknown index of refraction type 'abbe' (cauchy, sellmeier)");
  EXPECT_EQ(parseError({{"type", "cauchy"}, {"B", 0.004}}), at + "/A: missing required field");
  EXPECT_EQ(parseError({{"type", "cauchy"}, {"A", 1.5}, {"B", 0.004}, {"D", 0}}), at + "/D: unknown field");
  EXPECT_EQ(parseError({{"type", "cauchy"}, {"A", 0.9}, {"B", 0.05}}),
            at + ": index of refraction 0.999748 at 708.000000 nm is below 1");
  EXPECT_EQ(parseError({{"type", "sellmeier"}, {"B", {1, 0.2}}, {"C", {0.006, 0.02, 103}}}),
            at + "/B: expected an array of 3 numbers");
  EXPECT_EQ(parseError({{"type", "sellmeier"}, {"B", {1, 0.2, 1}}, {"C", {0.006, 0.02, "x"}}}),
            at + "/C: expected an array of 3 finite numbers");
  EXPECT_EQ(parseError({{"type", "sellmeier"}, {"B", {1, 0, 0}}, {"C", {0.25, 0, 0}}}),
            at + ": Sellmeier pole at 500.000000 nm (λ² = C) inside the wavelength range");
  const SpectrumContext ctx{"scene.json", ".", nullptr};
  try {
    parseMaterial({{"type", "dielectric"}}, ctx, "/materials/g", kRange);
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()), at + ": missing required field");
  }
}

}  // namespace
}  // namespace kasha
