#pragma once
// Test helpers for glossy (non-delta) elastic materials: χ² goodness of fit of direction sampling
// (docs/validation.md §3), sphere quadrature, and the consistency of one sample with pdf() and eval().
//
// Cells: (cos θ over [−1, 1], φ), both hemispheres, so samples on the wrong side are caught
// where the density is zero. Expected counts integrate Material::pdf over each cell with a
// sub×sub midpoint grid.
#include <algorithm>
#include <cmath>
#include <functional>
#include <optional>
#include <vector>

#include "core/rng.h"
#include "materials/material.h"
#include "tests/material_support.h"
#include "tests/support.h"

namespace kasha::test {

struct DirectionChi2Config {
  int nCos = 20, nPhi = 24, sub = 8;
  int samples = 200000;
  Vec2 uv{0.0f};  // texture coordinates of the hit (a textured material's per-hit model)
};

struct DirectionChi2Result {
  double p = 0.0;
  int failed = 0;            // samples that returned nothing
  double expectedMass = 0.0;  // ∫ pdf dω over the sphere (1 − the probability of failing)
};

// Physical order (ω_i, ω_o) of a direction sampled in `mode` from the known one.
inline std::pair<Vec3, Vec3> physicalOrder(TransportMode mode, const Vec3& wKnown, const Vec3& wSampled) {
  return mode == TransportMode::Radiance ? std::make_pair(wSampled, wKnown) : std::make_pair(wKnown, wSampled);
}

// ∫_S² g(ω) dω by the midpoint rule in (cos θ, φ).
inline double sphereQuadrature(int nCos, int nPhi, const std::function<double(const Vec3&)>& g) {
  const double dc = 2.0 / nCos, dp = 2.0 * kPi / nPhi;
  double sum = 0.0;
  for (int i = 0; i < nCos; ++i)
    for (int j = 0; j < nPhi; ++j) sum += g(dirFromCosPhi(float(-1.0 + (i + 0.5) * dc), float((j + 0.5) * dp)));
  return sum * dc * dp;
}

inline DirectionChi2Result directionChi2(const Material& material, TransportMode mode, const Vec3& wKnown, float lambda,
                                         uint64_t seed, const DirectionChi2Config& c = {}) {
  const Bsdf m = localBsdf(material, lambda, c.uv);
  const int nCells = c.nCos * c.nPhi;
  std::vector<double> observed(size_t(nCells), 0.0), expected(size_t(nCells), 0.0);
  DirectionChi2Result res;
  Rng rng(seed, 3);
  for (int s = 0; s < c.samples; ++s) {
    const std::optional<ScatterSample> smp =
        m.sample(mode, wKnown, lambda, Vec3(rng.uniform(), rng.uniform(), rng.uniform()));
    if (!smp) {
      ++res.failed;
      continue;
    }
    const int ic = std::clamp(int((smp->w.z + 1.0f) * 0.5f * float(c.nCos)), 0, c.nCos - 1);
    float phi = std::atan2(smp->w.y, smp->w.x);
    if (phi < 0.0f) phi += 2.0f * kPi;
    const int ip = std::clamp(int(phi / (2.0f * kPi) * float(c.nPhi)), 0, c.nPhi - 1);
    observed[size_t(ic * c.nPhi + ip)] += 1.0;
  }
  const double dc = 2.0 / c.nCos, dp = 2.0 * kPi / c.nPhi;
  const double sdc = dc / c.sub, sdp = dp / c.sub;
  for (int ic = 0; ic < c.nCos; ++ic)
    for (int ip = 0; ip < c.nPhi; ++ip)
      for (int a = 0; a < c.sub; ++a)
        for (int b = 0; b < c.sub; ++b) {
          const Vec3 w = dirFromCosPhi(float(-1.0 + ic * dc + (a + 0.5) * sdc), float(ip * dp + (b + 0.5) * sdp));
          const auto [wi, wo] = physicalOrder(mode, wKnown, w);
          const double mass = m.pdf({mode, SpectralLobe::Elastic, lambda, lambda}, wi, wo).pdf * sdc * sdp;
          expected[size_t(ic * c.nPhi + ip)] += c.samples * mass;
          res.expectedMass += mass;
        }
  res.p = chi2PValue(observed, expected);
  return res;
}

// Mean sampled weight f·|cos θ_sampled|/pdf from (wKnown, λ) (failed samples count 0), with its
// standard error over 20 batches of 5000: a Monte Carlo estimate of the directional albedo.
inline BatchStats sampledAlbedo(const Material& material, TransportMode mode, const Vec3& wKnown, float lambda, uint64_t seed) {
  const Bsdf m = localBsdf(material, lambda);
  Rng rng(seed);
  std::vector<double> batches;
  for (int b = 0; b < 20; ++b) {
    double sum = 0.0;
    const int n = 5000;
    for (int k = 0; k < n; ++k)
      if (auto s = m.sample(mode, wKnown, lambda, Vec3(rng.uniform(), rng.uniform(), rng.uniform())))
        sum += s->f * std::abs(s->w.z) / s->pdf;
    batches.push_back(sum / n);
  }
  return batchStats(batches);
}

// Checks one elastic sample from (wKnown, λ) against pdf() both ways and eval(); returns its
// weight f·|cos θ_sampled|/pdf. relRev: tolerance of the reverse density, recomputed from the
// sampled side (rounding of the half vector).
inline double expectConsistentSample(const Material& material, TransportMode mode, const Vec3& wKnown, float lambda,
                                     const ScatterSample& s, double relRev) {
  const Bsdf m = localBsdf(material, lambda);
  EXPECT_FALSE(s.specular);
  EXPECT_EQ(s.lobe, SpectralLobe::Elastic);
  EXPECT_EQ(s.lambda, lambda);
  const auto [wi, wo] = physicalOrder(mode, wKnown, s.w);
  const ScatterDensity d = m.pdf({mode, SpectralLobe::Elastic, lambda, lambda}, wi, wo);
  EXPECT_TRUE(close(s.pdf, d.pdf, 1e-4));
  EXPECT_TRUE(close(s.pdfRev, d.pdfRev, relRev));
  EXPECT_EQ(d.pdfRev, m.pdf({flip(mode), SpectralLobe::Elastic, lambda, lambda}, wi, wo).pdf);
  EXPECT_TRUE(close(s.f, m.eval({mode, SpectralLobe::Elastic, lambda, lambda}, wi, wo), 1e-6));
  return s.f * std::abs(s.w.z) / s.pdf;
}

}  // namespace kasha::test
