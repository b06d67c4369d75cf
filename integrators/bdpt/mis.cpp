#include "integrators/bdpt/mis.h"

namespace kasha::bdpt {
namespace {

bool allElastic(const FullPath& p) {
  for (size_t i = 1; i + 1 < p.v.size(); ++i)
    if (p.v[i].lobe != SpectralLobe::Elastic) return false;
  return true;
}

// Density of the full path under strategy s (docs/bdpt-mis.md eq. 3).
double density(const FullPath& p, int s) {
  const int k = int(p.v.size()) - 1;
  double d = 1.0;
  if (s == 1 && k >= 2) {
    d = p.specCam1 * p.pdfNee;
  } else {
    for (int i = 0; i < s; ++i) d *= p.v[size_t(i)].pdfLight;
  }
  for (int i = (s == 1 && k >= 2) ? 1 : s; i <= k; ++i) d *= p.v[size_t(i)].pdfCam;
  return d;
}

}  // namespace

bool strategyValid(const FullPath& p, int s) {
  const int k = int(p.v.size()) - 1;
  const bool independent = p.mode == WavelengthMode::Independent;
  if (s < 0 || s > k) return false;
  if (s == 0) return p.v[0].pdfCam > 0.0;  // the camera subpath hits the emitter
  if (k == 1) return p.lightSeenByPinhole;  // s = 1, t = 1: the light seen directly
  if (s == 1) return p.v[1].connectible && p.pdfNee > 0.0;  // next-event estimation
  if (s == k) {  // t = 1: light tracing; x_{k-1}'s lobe is evaluated, so it must be elastic
    if (!p.v[size_t(k - 1)].connectible) return false;
    return independent ? p.v[size_t(k - 1)].lobe == SpectralLobe::Elastic : allElastic(p);
  }
  // 2 ≤ s ≤ k − 1: both connection vertices evaluated; the connecting segment's wavelength must be
  // sampled exactly once: by one side through an elastic connection vertex (Independent), or
  // shared by the whole elastic path (Shared).
  const FullVertex& a = p.v[size_t(s - 1)];
  const FullVertex& b = p.v[size_t(s)];
  if (!a.connectible || !b.connectible) return false;
  if (!independent) return allElastic(p);
  return (a.lobe == SpectralLobe::Fluorescent) != (b.lobe == SpectralLobe::Fluorescent);
}

float misWeight(const FullPath& p, int s) {
  if (!strategyValid(p, s)) return 0.0f;
  const int k = int(p.v.size()) - 1;
  const double own = density(p, s);
  if (!(own > 0.0)) return 0.0f;
  double sum = 0.0;
  for (int i = 0; i <= k; ++i) {
    if (!strategyValid(p, i)) continue;
    const double r = density(p, i) / own;  // power heuristic, β = 2
    sum += r * r;
  }
  return float(1.0 / sum);
}

}  // namespace kasha::bdpt
