#include "integrators/bdpt/mis.h"

namespace kasha::bdpt {
namespace {

bool allElastic(const FullPath& p) {
  for (size_t i = 1; i + 1 < p.v.size(); ++i)
    if (p.v[i].lobe != SpectralLobe::Elastic) return false;
  return true;
}

// Density of the full path under strategy s (docs/bdpt-mis.md eqs. 2, 3 and 6).
double density(const FullPath& p, int s, Variant variant) {
  const int k = int(p.v.size()) - 1;
  const bool nee = s == 1 && k >= 2 && variant == Variant::kStandard;
  double d = 1.0;
  if (nee) {
    d = p.specCam1 * p.pdfNee;
  } else {
    for (int i = 0; i < s; ++i) d *= p.v[size_t(i)].pdfLight;
  }
  for (int i = nee ? 1 : s; i <= k; ++i) d *= p.v[size_t(i)].pdfCam;
  if (s == k && k >= 2) d *= p.specLightLast;  // t = 1 samples x_{k−1}'s event on the light side
  // Both sides sampled the connecting group's wavelength; the kernel accepts a window ε_h of the
  // camera side's (docs/bdpt-mis.md eq. 6).
  if (variant == Variant::kMollified) d *= p.mollifyWidth;
  return d;
}

}  // namespace

bool strategyValid(const FullPath& p, int s, Variant variant) {
  const int k = int(p.v.size()) - 1;
  const bool independent = p.mode == WavelengthMode::Independent;
  if (s < 0 || s > k) return false;
  if (variant == Variant::kMollified) {  // two elastic connection vertices, wavelengths chosen apart
    if (!independent || !(p.mollifyWidth > 0.0) || s < 2 || s > k - 1) return false;
    const FullVertex& a = p.v[size_t(s - 1)];
    const FullVertex& b = p.v[size_t(s)];
    return a.connectible && b.connectible && a.lobe == SpectralLobe::Elastic && b.lobe == SpectralLobe::Elastic;
  }
  if (s == 0) return p.v[0].pdfCam > 0.0;  // the camera subpath hits the emitter
  if (k == 1) return p.lightSeenByPinhole && variant == Variant::kStandard;  // s = t = 1: the light seen directly
  if (s == 1 && variant == Variant::kStandard) return p.v[1].connectible && p.pdfNee > 0.0;
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

float misWeight(const FullPath& p, int s, Variant variant) {
  if (!strategyValid(p, s, variant)) return 0.0f;
  const int k = int(p.v.size()) - 1;
  const double own = density(p, s, variant);
  if (!(own > 0.0)) return 0.0f;
  double sum = 0.0;
  auto add = [&](int i, Variant o) {
    if (!strategyValid(p, i, o)) return;
    const double r = density(p, i, o) / own;  // power heuristic, β = 2
    sum += r * r;
  };
  for (int i = 0; i <= k; ++i) add(i, Variant::kStandard);
  if (k >= 2) add(1, Variant::kLightVertex);
  for (int i = 2; i < k; ++i) add(i, Variant::kMollified);
  return float(1.0 / sum);
}

}  // namespace kasha::bdpt
