#include "integrators/bdpt/mis.h"

namespace kasha::bdpt {
namespace {

bool allElastic(const FullPath& p) {
  for (size_t i = 1; i + 1 < p.v.size(); ++i)
    if (p.v[i].lobe != SpectralLobe::Elastic) return false;
  return true;
}

// Density of the full path under strategy s (docs/bdpt-mis.md eq. 3).
double density(const FullPath& p, int s, SOne one) {
  const int k = int(p.v.size()) - 1;
  const bool nee = s == 1 && k >= 2 && one == SOne::kNee;
  double d = 1.0;
  if (nee) {
    d = p.specCam1 * p.pdfNee;
  } else {
    for (int i = 0; i < s; ++i) d *= p.v[size_t(i)].pdfLight;
  }
  for (int i = nee ? 1 : s; i <= k; ++i) d *= p.v[size_t(i)].pdfCam;
  if (s == k && k >= 2) d *= p.specLightLast;  // t = 1 samples x_{k−1}'s event on the light side
  return d;
}

}  // namespace

bool strategyValid(const FullPath& p, int s, SOne one) {
  const int k = int(p.v.size()) - 1;
  const bool independent = p.mode == WavelengthMode::Independent;
  if (s < 0 || s > k) return false;
  if (s == 0) return p.v[0].pdfCam > 0.0;  // the camera subpath hits the emitter
  if (k == 1) return p.lightSeenByPinhole && one == SOne::kNee;  // s = t = 1: the light seen directly
  if (s == 1 && one == SOne::kNee) return p.v[1].connectible && p.pdfNee > 0.0;
  if (s == 1)  // the light subpath's vertex, at its own wavelength: x_1 must bridge it (Independent)
    return independent && p.lightVertexConnectible && p.v[1].connectible && p.v[1].lobe == SpectralLobe::Fluorescent;
  if (s == k) {  // t = 1: light tracing, x_{k−1}'s event sampled by the light side
    if (!p.v[size_t(k - 1)].connectible || !(p.specLightLast > 0.0)) return false;
    return independent || allElastic(p);
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

float misWeight(const FullPath& p, int s, SOne one) {
  if (!strategyValid(p, s, one)) return 0.0f;
  const int k = int(p.v.size()) - 1;
  const double own = density(p, s, one);
  if (!(own > 0.0)) return 0.0f;
  double sum = 0.0;
  auto add = [&](int i, SOne o) {
    if (!strategyValid(p, i, o)) return;
    const double r = density(p, i, o) / own;  // power heuristic, β = 2
    sum += r * r;
  };
  for (int i = 0; i <= k; ++i) add(i, SOne::kNee);
  if (k >= 2) add(1, SOne::kLightVertex);
  return float(1.0 / sum);
}

}  // namespace kasha::bdpt
