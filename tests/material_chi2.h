#pragma once
// χ² goodness-of-fit machinery shared by the material tests (docs/validation.md §3):
// quadrature over the sphere, the physical order of a sampled event, and a
// joint (lobe, direction, wavelength) χ² test of Bsdf::sample against Bsdf::pdf,
// through the Bsdf a material builds at a hit (or any Bsdf in the world frame).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <optional>
#include <vector>

#include "core/rng.h"
#include "core/spectrum.h"
#include "materials/material.h"
#include "tests/material_support.h"
#include "tests/support.h"

namespace kasha::test {

// Integral over the whole sphere of g(ω) dω by the midpoint rule in (cos θ, φ),
// where dω = dcos θ dφ. Exact (up to rounding) for any g that is linear in cos
// θ on each hemisphere and independent of φ, which every diffuse density and
// f·cos is.
inline double sphereIntegral(int nCos, int nPhi, const std::function<double(const Vec3&)>& g) {
  const double dc = 2.0 / nCos, dp = 2.0 * kPi / nPhi;
  double sum = 0.0;
  for (int i = 0; i < nCos; ++i)
    for (int j = 0; j < nPhi; ++j)
      sum += g(dirFromCosPhi(float(-1.0 + (i + 0.5) * dc), float((j + 0.5) * dp))) * dc * dp;
  return sum;
}

// Physical order of an event sampled in `mode` from the known side.
struct Event {
  Vec3 wi, wo;
  float lambdaIn, lambdaOut;
};
inline Event physical(TransportMode mode, const Vec3& wKnown, float lKnown, const Vec3& wOther, float lOther) {
  if (mode == TransportMode::Radiance) return {wOther, wKnown, lOther, lKnown};
  return {wKnown, wOther, lKnown, lOther};
}

// ---------------------------------------------------------------------------------------------
// χ² goodness of fit of Material::sample over (lobe, direction, wavelength)
// jointly.
//
// Cells: directions by (cos θ over [−1, 1], φ) — the wrong hemisphere is
// included and expects nothing — times, for the fluorescent lobe, 10 nm
// wavelength bins; the elastic lobe is one categorical value per direction cell
// (its wavelength is the known one, a Dirac mass). Expected counts integrate
// Material::pdf over each cell with a sub-grid (1 nm in wavelength, 2×2 in
// direction).

struct Chi2Config {
  WavelengthRange range{360.0f, 830.0f};
  int nCos = 10, nPhi = 12;
  float binNm = 10.0f;
  int subDir = 2, subNm = 10;
  int samples = 400000;
  // Directional sampling may reject (a lobe about the mirror direction that
  // crosses the surface): failed samples then form one more cell, expecting
  // n·(1 − ∫pdf).
  bool rejectionCell = false;
};

struct Chi2Result {
  double p = 0.0;
  int failed = 0;             // samples that returned nothing
  double expectedMass = 0.0;  // ∫ pdf over all cells (1 − the probability of failing)
};

inline int dirCell(const Chi2Config& c, const Vec3& w) {
  const int ic = std::clamp(int((w.z + 1.0f) * 0.5f * float(c.nCos)), 0, c.nCos - 1);
  float phi = std::atan2(w.y, w.x);
  if (phi < 0.0f) phi += 2.0f * kPi;
  const int ip = std::clamp(int(phi / (2.0f * kPi) * float(c.nPhi)), 0, c.nPhi - 1);
  return ic * c.nPhi + ip;
}

// Of a Bsdf whose local frame is the world frame (a material's at a hit, or a medium point's).
inline Chi2Result jointChi2(const Bsdf& m, TransportMode mode, const Vec3& wKnown, float lKnown, uint64_t seed,
                            const Chi2Config& c = {}) {
  const int nL = int(std::lround(c.range.width() / c.binNm));
  const int nDir = c.nCos * c.nPhi;
  // Layout: [fluorescent: dir * nL + l] [elastic: dir] [outside the range: 1]
  const size_t elasticBase = size_t(nDir) * nL, outside = elasticBase + nDir;
  std::vector<double> observed(outside + 1, 0.0), expected(outside + 1, 0.0);

  Chi2Result res;
  Rng rng(seed, 7);
  for (int s = 0; s < c.samples; ++s) {
    const Vec3 u(rng.uniform(), rng.uniform(), rng.uniform());
    const std::optional<ScatterSample> smp = m.sample(mode, wKnown, lKnown, u);
    if (!smp) {
      ++res.failed;
      continue;
    }
    const int d = dirCell(c, smp->w);
    if (smp->lobe == SpectralLobe::Elastic) {
      EXPECT_EQ(smp->lambda, lKnown) << "elastic events keep the known wavelength exactly";
      observed[elasticBase + d] += 1.0;
    } else if (!(smp->lambda >= c.range.min && smp->lambda < c.range.max)) {
      observed[outside] += 1.0;
    } else {
      const int l = std::clamp(int((smp->lambda - c.range.min) / c.binNm), 0, nL - 1);
      observed[size_t(d) * nL + l] += 1.0;
    }
  }

  const double dc = 2.0 / c.nCos, dp = 2.0 * kPi / c.nPhi;
  const double subDc = dc / c.subDir, subDp = dp / c.subDir, subNm = double(c.binNm) / c.subNm;
  const double n = c.samples;
  for (int ic = 0; ic < c.nCos; ++ic)
    for (int ip = 0; ip < c.nPhi; ++ip) {
      const int d = ic * c.nPhi + ip;
      for (int a = 0; a < c.subDir; ++a)
        for (int b = 0; b < c.subDir; ++b) {
          const Vec3 w = dirFromCosPhi(float(-1.0 + ic * dc + (a + 0.5) * subDc), float(ip * dp + (b + 0.5) * subDp));
          const double dw = subDc * subDp;
          const Event ee = physical(mode, wKnown, lKnown, w, lKnown);
          expected[elasticBase + d] +=
              n * dw * m.pdf({mode, SpectralLobe::Elastic, ee.lambdaIn, ee.lambdaOut}, ee.wi, ee.wo).pdf;
          if (m.has(BsdfFlags::Fluorescent))  // otherwise every fluorescent cell expects 0
            for (int l = 0; l < nL; ++l)
              for (int k = 0; k < c.subNm; ++k) {
                const float lambda = float(c.range.min + l * double(c.binNm) + (k + 0.5) * subNm);
                const Event ev = physical(mode, wKnown, lKnown, w, lambda);
                expected[size_t(d) * nL + l] +=
                    n * dw * subNm *
                    m.pdf({mode, SpectralLobe::Fluorescent, ev.lambdaIn, ev.lambdaOut}, ev.wi, ev.wo).pdf;
              }
        }
    }
  double sum = 0.0;
  for (const double e : expected) sum += e;
  res.expectedMass = sum / n;
  if (c.rejectionCell) {
    observed.push_back(res.failed);
    expected.push_back(std::max(0.0, n - sum));
  }
  res.p = test::chi2PValue(observed, expected);
  return res;
}

inline Chi2Result jointChi2(const Material& material, TransportMode mode, const Vec3& wKnown, float lKnown,
                            uint64_t seed, const Chi2Config& c = {}) {
  return jointChi2(localBsdf(material, lKnown), mode, wKnown, lKnown, seed, c);
}

}  // namespace kasha::test
