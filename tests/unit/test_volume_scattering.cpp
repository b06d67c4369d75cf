// The collision kernel of a medium (materials/volume_scattering.h, docs/media.md §2) against
// closed forms written here from its definition, not from its code:
//   - Henyey–Greenstein sampling: χ² of the sampled directions against the exact CDF of the angle
//     about the axis, P(cos θ ≤ μ) = (1 − g²)/(2g)·(1/√(1 + g² − 2gμ) − 1/(1 + g)), uniform in
//     azimuth; directionPdf against the HG formula; both transport modes, g from −0.9 to 0.9;
//   - the spectral stage: χ² of sampleSpectral against spectralPdf, and spectralPdf,
//     fluorescenceProbability and albedoWeight against Jung18-style eqs. 6–7 (media.md eq. 5)
//     evaluated from the spectra by quadrature; one and two fluorophores, both modes;
//   - a whole event: f/pdf = A_el + A_fl, and the joint (lobe, direction, wavelength) χ² of
//     tests/material_chi2.h through the Bsdf of a medium point.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <vector>

#include "core/medium.h"
#include "core/rng.h"
#include "core/sampling.h"
#include "materials/bsdf.h"
#include "materials/volume_scattering.h"
#include "tests/material_chi2.h"
#include "tests/material_support.h"
#include "tests/support.h"

namespace kasha {
namespace {

const WavelengthRange kRange{360.0f, 830.0f};
constexpr double kPiD = 3.14159265358979323846;

MediumParams oneFluorophore(float g) {
  MediumParams p;
  p.absorption = Spectrum::constant(0.2f);
  p.scattering = Spectrum::piecewiseLinear({360.0f, 830.0f}, {0.5f, 1.5f});
  p.g = g;
  p.fluorophores.push_back({Spectrum::gaussian(420.0f, 60.0f, 2.0f), Spectrum::gaussian(560.0f, 50.0f, 3.0f), 0.8f});
  return p;
}

MediumParams twoFluorophores(float g) {
  MediumParams p = oneFluorophore(g);
  p.fluorophores.push_back({Spectrum::box(480.0f, 540.0f, 0.7f), Spectrum::gaussian(650.0f, 40.0f), 0.5f});
  return p;
}

// ∫ s over the range by the midpoint rule on a 0.01 nm grid.
double integral(const Spectrum& s) {
  double sum = 0.0;
  for (double l = kRange.min + 0.005; l < kRange.max; l += 0.01) sum += s(float(l)) * 0.01;
  return sum;
}

// The spectral stage written from its definition (media.md eq. 5, Jung18 eqs. 6–7).
struct SpectralStage {
  const MediumParams& p;
  std::vector<double> absorptionIntegral, emissionIntegral;
  explicit SpectralStage(const MediumParams& params) : p(params) {
    for (const Fluorophore& f : p.fluorophores) {
      absorptionIntegral.push_back(integral(f.absorption));
      emissionIntegral.push_back(integral(f.emission));
    }
  }
  double normalisedEmission(size_t k, float lambda) const { return p.fluorophores[k].emission(lambda) / emissionIntegral[k]; }
  // A_fl: the fluorescent kernel (times 4π) integrated over the unknown wavelength.
  double fluorescent(TransportMode mode, float known) const {
    double a = 0.0;
    for (size_t k = 0; k < p.fluorophores.size(); ++k) {
      const Fluorophore& f = p.fluorophores[k];
      a += mode == TransportMode::Radiance ? f.yield * normalisedEmission(k, known) * absorptionIntegral[k]
                                           : f.absorption(known) * f.yield;
    }
    return a;
  }
  double elastic(float known) const { return p.scattering(known); }
  double total(TransportMode mode, float known) const { return elastic(known) + fluorescent(mode, known); }
  // Density per nm of the fluorescent lobe's other wavelength, times the lobe's probability.
  double fluorescentPdf(TransportMode mode, float known, float other) const {
    const float in = mode == TransportMode::Radiance ? other : known, out = mode == TransportMode::Radiance ? known : other;
    double f = 0.0;
    for (size_t k = 0; k < p.fluorophores.size(); ++k)
      f += p.fluorophores[k].absorption(in) * p.fluorophores[k].yield * normalisedEmission(k, out);
    return f / total(mode, known);
  }
};

// ---------------------------------------------------------------------------------------------
// Henyey–Greenstein

double hgExact(double mu, double g) {
  return (1.0 - g * g) / (4.0 * kPiD * std::pow(1.0 + g * g - 2.0 * g * mu, 1.5));
}

double hgCdf(double mu, double g) {
  if (std::abs(g) < 1e-6) return 0.5 * (1.0 + mu);
  return (1.0 - g * g) / (2.0 * g) * (1.0 / std::sqrt(1.0 + g * g - 2.0 * g * mu) - 1.0 / (1.0 + g));
}

// χ² of directions sampled by `sample` about `axis` in cells of (cos θ, φ) against the exact HG
// distribution; φ is measured in a frame built here, as the distribution is uniform in azimuth.
void expectHenyeyGreenstein(const std::function<Vec3(Vec2)>& sample, const Vec3& axis, double g, uint64_t seed) {
  const int nCos = 40, nPhi = 8, n = 100000;
  const Vec3 helper = std::abs(axis.x) < 0.9f ? Vec3(1, 0, 0) : Vec3(0, 1, 0);
  const Vec3 s = glm::normalize(glm::cross(helper, axis)), t = glm::cross(axis, s);
  std::vector<double> observed(size_t(nCos * nPhi), 0.0), expected(observed.size(), 0.0);
  Rng rng(seed, 3);
  for (int i = 0; i < n; ++i) {
    const Vec3 w = sample(Vec2(rng.uniform(), rng.uniform()));
    ASSERT_NEAR(glm::length(w), 1.0f, 1e-4f);
    const float mu = glm::dot(w, axis);
    double phi = std::atan2(double(glm::dot(w, t)), double(glm::dot(w, s)));
    if (phi < 0.0) phi += 2.0 * kPiD;
    const int ic = std::clamp(int((mu + 1.0f) * 0.5f * nCos), 0, nCos - 1);
    const int ip = std::clamp(int(phi / (2.0 * kPiD) * nPhi), 0, nPhi - 1);
    observed[size_t(ic * nPhi + ip)] += 1.0;
  }
  for (int ic = 0; ic < nCos; ++ic) {
    const double mass = hgCdf(-1.0 + 2.0 * (ic + 1) / nCos, g) - hgCdf(-1.0 + 2.0 * ic / nCos, g);
    for (int ip = 0; ip < nPhi; ++ip) expected[size_t(ic * nPhi + ip)] = n * mass / nPhi;
  }
  EXPECT_GT(test::chi2PValue(observed, expected), 1e-3);
}

const float kGs[] = {-0.9f, -0.5f, -5e-4f, 0.0f, 0.3f, 0.7f, 0.9f};

TEST(HenyeyGreenstein, SamplingFollowsTheExactDistributionAboutTheAxis) {
  uint64_t seed = 1;
  for (const float g : kGs) {
    SCOPED_TRACE("g = " + std::to_string(g));
    const Vec3 axis = glm::normalize(Vec3(0.3f, -0.5f, 0.8f));
    expectHenyeyGreenstein([&](Vec2 u) { return sampleHenyeyGreenstein(axis, g, u); }, axis, g, seed++);
  }
}

TEST(HenyeyGreenstein, PhaseFunctionIsTheFormulaAndNormalised) {
  for (const float g : kGs) {
    for (double mu = -1.0; mu <= 1.0; mu += 0.125)
      EXPECT_TRUE(test::close(henyeyGreenstein(float(mu), g), hgExact(mu, g), 1e-4)) << "g " << g << " μ " << mu;
    // ∫ p dω = 2π ∫ p dμ (midpoint rule, fine enough for g = ±0.9's peak).
    double sum = 0.0;
    const int m = 200000;
    for (int i = 0; i < m; ++i) sum += henyeyGreenstein(float(-1.0 + (i + 0.5) * 2.0 / m), g) * 2.0 / m;
    EXPECT_NEAR(2.0 * kPiD * sum, 1.0, 1e-3) << "g " << g;
  }
}

// VolumeScattering's directional stage, elastic lobe: as cos θ = −ω_i·ω_o, the sampled direction
// is HG-distributed about −ω_known in both modes (ω_i about −ω_o, or ω_o about −ω_i); its pdf is
// directionPdf and the HG formula.
TEST(VolumeScatteringDirection, ElasticIsHenyeyGreensteinAboutTheContinuingDirection) {
  uint64_t seed = 100;
  const Vec3 wKnown = glm::normalize(Vec3(-0.2f, 0.7f, 0.4f));
  for (const float g : kGs) {
    const Medium medium("m", oneFluorophore(g), kRange);
    const VolumeScattering vs(medium);
    for (const TransportMode mode : {TransportMode::Radiance, TransportMode::Importance}) {
      SCOPED_TRACE(std::string(toString(mode)) + " g = " + std::to_string(g));
      expectHenyeyGreenstein(
          [&](Vec2 u) {
            const std::optional<DirectionSample> ds =
                vs.sampleDirection({mode, SpectralLobe::Elastic, 500, 500}, wKnown, u);
            EXPECT_TRUE(ds.has_value());
            if (!ds) return Vec3(0.0f, 0.0f, 1.0f);
            const double mu = -glm::dot(wKnown, ds->w);
            EXPECT_TRUE(test::close(ds->pdf, hgExact(mu, g), 2e-3, 1e-6));
            EXPECT_TRUE(
                test::close(ds->pdf, vs.directionPdf({mode, SpectralLobe::Elastic, 500, 500}, wKnown, ds->w), 1e-5));
            return ds->w;
          },
          -wKnown, g, seed++);
    }
  }
}

// Isotropic re-emission: uniform over the sphere, the HG distribution with g = 0.
TEST(VolumeScatteringDirection, FluorescentIsUniformOverTheSphere) {
  const Medium medium("m", oneFluorophore(0.8f), kRange);
  const VolumeScattering vs(medium);
  const Vec3 wKnown = glm::normalize(Vec3(0.5f, 0.5f, -0.2f));
  uint64_t seed = 200;
  for (const TransportMode mode : {TransportMode::Radiance, TransportMode::Importance}) {
    SCOPED_TRACE(toString(mode));
    expectHenyeyGreenstein(
        [&](Vec2 u) {
          const std::optional<DirectionSample> ds =
              vs.sampleDirection({mode, SpectralLobe::Fluorescent, 420, 560}, wKnown, u);
          EXPECT_TRUE(ds.has_value());
          if (!ds) return Vec3(0.0f, 0.0f, 1.0f);
          EXPECT_NEAR(ds->pdf, 1.0 / (4.0 * kPiD), 1e-7);
          EXPECT_NEAR(vs.directionPdf({mode, SpectralLobe::Fluorescent, 420, 560}, wKnown, ds->w), 1.0 / (4.0 * kPiD),
                      1e-7);
          return ds->w;
        },
        -wKnown, 0.0, seed++);
  }
}

// ---------------------------------------------------------------------------------------------
// The spectral stage

// Runs `check` for one and two fluorophores, both modes, and known wavelengths in the first
// absorption band, in the overlap of the second's absorption and the first's emission, in the
// emission bands, and where only elastic scattering happens.
void forEachCase(const std::function<void(const VolumeScattering&, const SpectralStage&, TransportMode, float)>& check) {
  for (const MediumParams& params : {oneFluorophore(0.3f), twoFluorophores(0.3f)}) {
    const Medium medium("m", params, kRange);
    const VolumeScattering vs(medium);
    const SpectralStage ref(params);
    for (const TransportMode mode : {TransportMode::Radiance, TransportMode::Importance})
      for (const float known : {420.0f, 500.0f, 560.0f, 650.0f, 800.0f}) {
        SCOPED_TRACE(std::to_string(params.fluorophores.size()) + " fluorophore(s), " + toString(mode) +
                     ", known λ = " + std::to_string(known));
        check(vs, ref, mode, known);
      }
  }
}

TEST(VolumeScatteringSpectral, DensitiesAndLobeProbabilityAreEq5) {
  forEachCase([](const VolumeScattering& vs, const SpectralStage& ref, TransportMode mode, float known) {
    const double total = ref.total(mode, known);
    EXPECT_TRUE(test::close(vs.albedoWeight(mode, known), total, 1e-3));
    EXPECT_TRUE(test::close(vs.fluorescenceProbability(mode, known), ref.fluorescent(mode, known) / total, 1e-3, 1e-6));
    EXPECT_TRUE(test::close(vs.spectralPdf(mode, known, known, SpectralLobe::Elastic), ref.elastic(known) / total, 1e-3));
    for (float other = 361.0f; other < 830.0f; other += 7.0f)
      EXPECT_TRUE(test::close(vs.spectralPdf(mode, known, other, SpectralLobe::Fluorescent),
                              ref.fluorescentPdf(mode, known, other), 1e-3, 1e-9))
          << "other λ " << other;
  });
}

// χ² of sampleSpectral's (lobe, wavelength) in 5 nm bins plus one elastic cell against
// spectralPdf, and its reported pdf against spectralPdf.
TEST(VolumeScatteringSpectral, SamplingFollowsSpectralPdf) {
  uint64_t seed = 300;
  forEachCase([&](const VolumeScattering& vs, const SpectralStage&, TransportMode mode, float known) {
    const int bins = 94, n = 100000, sub = 10;
    const float width = kRange.width() / bins;
    std::vector<double> observed(bins + 1, 0.0), expected(bins + 1, 0.0);
    Rng rng(seed++, 5);
    int fluorescent = 0;
    for (int i = 0; i < n; ++i) {
      const SpectralChoice s = vs.sampleSpectral(mode, known, rng.uniform());
      ASSERT_GT(s.pdf, 0.0f);
      if (s.lobe == SpectralLobe::Elastic) {
        ASSERT_EQ(s.lambda, known);
        ASSERT_TRUE(test::close(s.pdf, vs.spectralPdf(mode, known, known, SpectralLobe::Elastic), 1e-5));
        observed[bins] += 1.0;
        continue;
      }
      ++fluorescent;
      ASSERT_TRUE(kRange.contains(s.lambda)) << s.lambda;
      ASSERT_TRUE(test::close(s.pdf, vs.spectralPdf(mode, known, s.lambda, SpectralLobe::Fluorescent), 1e-4));
      observed[size_t(std::clamp(int((s.lambda - kRange.min) / width), 0, bins - 1))] += 1.0;
    }
    for (int b = 0; b < bins; ++b)
      for (int k = 0; k < sub; ++k)
        expected[size_t(b)] += n * width / sub *
                               vs.spectralPdf(mode, known, kRange.min + width * (b + (k + 0.5f) / sub),
                                              SpectralLobe::Fluorescent);
    expected[bins] = n * vs.spectralPdf(mode, known, known, SpectralLobe::Elastic);
    EXPECT_GT(test::chi2PValue(observed, expected), 1e-3);
    // The fluorescent lobe's frequency is fluorescenceProbability (binomial, 4σ).
    const double pFl = vs.fluorescenceProbability(mode, known);
    EXPECT_NEAR(double(fluorescent) / n, pFl, 4.0 * std::sqrt(pFl * (1.0 - pFl) / n) + 1e-9);
  });
}

// f/pdf of a whole sampled event (both stages) is A_el + A_fl at the known wavelength, whichever
// lobe, fluorophore and direction were drawn; and eval()/pdf() at the sampled event agree with it.
TEST(VolumeScatteringEvent, WeightOfASampledEventIsTheAlbedoWeight) {
  Rng rng(400, 1);
  forEachCase([&](const VolumeScattering& vs, const SpectralStage& ref, TransportMode mode, float known) {
    const double total = ref.total(mode, known);
    int fluorescent = 0;
    for (int i = 0; i < 2000; ++i) {
      const Vec3 wKnown = sampleUniformSphere(Vec2(rng.uniform(), rng.uniform()));
      const std::optional<ScatterSample> s =
          vs.sample(mode, wKnown, known, Vec3(rng.uniform(), rng.uniform(), rng.uniform()));
      ASSERT_TRUE(s.has_value());
      fluorescent += s->lobe == SpectralLobe::Fluorescent;
      ASSERT_TRUE(test::close(s->f / s->pdf, total, 2e-3)) << "lobe " << int(s->lobe) << " λ " << s->lambda;
      const test::Event e = test::physical(mode, wKnown, known, s->w, s->lambda);
      ASSERT_TRUE(test::close(vs.eval({mode, s->lobe, e.lambdaIn, e.lambdaOut}, e.wi, e.wo), s->f, 1e-5));
      ASSERT_TRUE(test::close(vs.pdf({mode, s->lobe, e.lambdaIn, e.lambdaOut}, e.wi, e.wo).pdf, s->pdf, 1e-4));
    }
    if (ref.fluorescent(mode, known) > 0.05 * total) {
      EXPECT_GT(fluorescent, 0);
    }
  });
}

// The joint (lobe, direction, wavelength) χ² of tests/material_chi2.h through the Bsdf of a medium
// point, as Scene::mediumBsdf builds it (world frame).
TEST(VolumeScatteringEvent, JointChi2ThroughTheBsdf) {
  const Medium medium("m", twoFluorophores(0.3f), kRange);
  const VolumeScattering vs(medium);
  const Frame world{Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)};
  const Bsdf bsdf(vs, HitContext{Vec2(0.0f), world, world, {}, MeshPoint{}, Vec3(0.0f), Vec3(0.0f)});
  ASSERT_TRUE(bsdf.has(BsdfFlags::Volume));
  EXPECT_EQ(bsdf.cosineFactor(Vec3(0, 0, 1)), 1.0f);
  EXPECT_EQ(bsdf.cosineFactor(glm::normalize(Vec3(1, 1, 0.01f))), 1.0f);
  uint64_t seed = 500;
  for (const TransportMode mode : {TransportMode::Radiance, TransportMode::Importance})
    for (const float known : {420.0f, 560.0f}) {
      SCOPED_TRACE(std::string(toString(mode)) + " known λ = " + std::to_string(known));
      test::Chi2Config cfg;
      cfg.samples = 200000;
      const test::Chi2Result r = test::jointChi2(bsdf, mode, glm::normalize(Vec3(0.3f, -0.4f, 0.6f)), known, seed++, cfg);
      EXPECT_GT(r.p, 1e-3);
      EXPECT_EQ(r.failed, 0);
      EXPECT_NEAR(r.expectedMass, 1.0, 2e-3);
    }
}

}  // namespace
}  // namespace kasha
