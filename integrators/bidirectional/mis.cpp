#include "integrators/bidirectional/mis.h"

namespace kasha::bidir {
namespace {

bool allElastic(const FullPath& p) {
  for (size_t i = 1; i + 1 < p.v.size(); ++i)
    if (p.v[i].lobe != SpectralLobe::Elastic) return false;
  return true;
}

// Whether x_s is the path's first gather vertex: every vertex between it and the camera specular.
bool gatherVertex(const FullPath& p, int s) {
  for (size_t i = size_t(s) + 1; i + 1 < p.v.size(); ++i)
    if (p.v[i].connectible) return false;
  return true;
}

bool validGiven(const FullPath& p, int s, Variant variant, bool elastic) {
  const int k = int(p.v.size()) - 1;
  if (s < 0 || s > k) return false;
  if (isMerge(variant)) {  // both sides sample x_s
    const FullVertex& x = p.v[size_t(s)];
    if (s < 1 || s > k - 1 || !x.connectible || !x.mergeable || !(etaOf(p.mergeEta, variant, gatherVertex(p, s), x.volume) > 0.0))
      return false;
    const bool fluorescent = p.v[size_t(s)].lobe == SpectralLobe::Fluorescent;
    if (isBeam(variant) && !(x.cameraBeam > 0.0)) return false;
    if (isPhotonBeam(variant) && !(x.lightBeam > 0.0 && x.beamSine > 0.0)) return false;
    if (isBeam(variant)) return isOwnBeam(variant) ? p.families.independent && fluorescent : p.families.shared && elastic;
    if (variant == Variant::kMerge) return p.families.shared && elastic;
    if (variant == Variant::kMergeSplat) return p.families.independent && !fluorescent && s == k - 1;
    if (variant == Variant::kMergeOwn) return p.families.independent && fluorescent;
    return p.families.independent && !fluorescent && p.mollifyWidth > 0.0;
  }
  const bool own = variant != Variant::kStandard;  // every other variant is the independent family's
  if (own && !p.families.independent) return false;
  if (s == 0) return variant == Variant::kStandard && p.v[0].pdfCam > 0.0;  // the camera subpath hits the emitter
  if (!p.connections) return false;
  if (k == 1) {  // s = t = 1: the light seen directly, at the sensor's or the light's wavelength
    if (!p.lightSeenByPinhole) return false;
    return variant == Variant::kOwn || (variant == Variant::kStandard && p.families.shared);
  }
  switch (variant) {
    case Variant::kLightVertex:  // the light vertex's wavelength reaches the camera's through x_1's fluorescent lobe
      return s == 1 && p.lightVertexConnectible && p.v[1].connectible && p.v[1].lobe == SpectralLobe::Fluorescent;
    case Variant::kMollified: {  // two elastic connection vertices, wavelengths chosen apart
      if (!(p.mollifyWidth > 0.0) || s < 2 || s > k - 1) return false;
      const FullVertex& a = p.v[size_t(s - 1)];
      const FullVertex& b = p.v[size_t(s)];
      return a.connectible && b.connectible && a.lobe == SpectralLobe::Elastic && b.lobe == SpectralLobe::Elastic;
    }
    case Variant::kStandard:
      if (s == 1) return p.v[1].connectible && p.pdfNee > 0.0;  // next-event estimation
      // The shared family's light subpath and the camera's last group are one draw: exact only
      // when the path has one group (docs/bdpt-mis.md §4).
      if (!p.families.shared || !elastic) return false;
      break;
    case Variant::kOwn:
      if (s == 1) return false;
      break;
    case Variant::kMerge:
    case Variant::kMergeOwn:
    case Variant::kMergeMollified:
    case Variant::kMergeSplat:
    case Variant::kBeam:
    case Variant::kBeamOwn:
    case Variant::kPhotonBeam:
    case Variant::kPhotonBeamOwn:
      return false;  // decided above
  }
  if (s == k)  // t = 1: light tracing, x_{k−1}'s event sampled by the light side
    return p.v[size_t(k - 1)].connectible && p.specLightLast > 0.0;
  // 2 ≤ s ≤ k − 1: both connection vertices evaluated; the connecting segment's wavelength must be
  // sampled exactly once: shared by the whole elastic path, or by one side through an elastic
  // connection vertex (independent family).
  const FullVertex& a = p.v[size_t(s - 1)];
  const FullVertex& b = p.v[size_t(s)];
  if (!a.connectible || !b.connectible) return false;
  return variant == Variant::kStandard ||
         (a.lobe == SpectralLobe::Fluorescent) != (b.lobe == SpectralLobe::Fluorescent);
}

// Density of the path under strategy (s, variant) (docs/bdpt-mis.md eqs. 2, 3, 6 and §5's table),
// whether or not the strategy is valid.
double strategyDensity(const FullPath& p, int s, Variant variant) {
  const int k = int(p.v.size()) - 1;
  if (isMerge(variant)) {
    // Both sides sample x_s; the kernel accepts a disc of area π r² around it, one of N light
    // subpaths (η = N·π r², each kind's), and through an elastic x_s an own light vertex's wavelength within a
    // window ε_h of the camera's (as a mollified join, eq. 6).
    // A beam's: the camera side's free-flight factor at x_s replaced by the probability of its beam
    // reaching past x_s (docs/media-beams.md eq. B2), and a photon beam's the light side's too (eq. B4).
    double d = etaOf(p.mergeEta, variant, gatherVertex(p, s), p.v[size_t(s)].volume);
    if (isBeam(variant)) d *= p.v[size_t(s)].cameraBeam;
    if (isPhotonBeam(variant)) d *= p.v[size_t(s)].lightBeam * p.v[size_t(s)].beamSine;
    for (int i = 0; i <= s; ++i) d *= p.v[size_t(i)].pdfLight;
    for (int i = s; i <= k; ++i) d *= p.v[size_t(i)].pdfCam;
    if (variant == Variant::kMerge || variant == Variant::kBeam || variant == Variant::kPhotonBeam) return d * p.sensorPdf * p.sharedChoice * p.laneGain;
    if (variant == Variant::kMergeSplat) return d * p.ownChoice;  // the light draws every group's wavelength
    d *= p.sensorPdf * p.ownChoice;
    return variant == Variant::kMergeMollified ? d * p.mollifyWidth : d;
  }
  const bool nee = s == 1 && k >= 2 && variant == Variant::kStandard;
  double d = 1.0;
  if (nee) {
    d = p.specCam1 * p.pdfNee;
  } else {
    for (int i = 0; i < s; ++i) d *= p.v[size_t(i)].pdfLight;
  }
  for (int i = nee ? 1 : s; i <= k; ++i) d *= p.v[size_t(i)].pdfCam;
  if (s == k && k >= 2) d *= p.specLightLast;  // t = 1 samples x_{k−1}'s event on the light side
  // The light choice and the wavelength densities: next-event estimation chooses the light with
  // cameraChoice, the shared light subpath with sharedChoice, the independent family the light
  // with the first group's wavelength; every
  // strategy but the independent family's t = 1 has the sensor draw the last group's wavelength.
  if (s == 0) return d * p.sensorPdf * p.laneGain;
  if (variant == Variant::kStandard) return d * p.sensorPdf * (nee ? p.cameraChoice : p.sharedChoice) * p.laneGain;
  if (s == k) return d * p.ownChoice;
  d *= p.sensorPdf * p.ownChoice;
  // Both sides sampled the connecting group's wavelength; the kernel accepts a window ε_h of the
  // camera side's (docs/bdpt-mis.md eq. 6).
  if (variant == Variant::kMollified) d *= p.mollifyWidth;
  return d;
}

}  // namespace

bool strategyValid(const FullPath& p, int s, Variant variant) { return validGiven(p, s, variant, allElastic(p)); }

float misWeight(const FullPath& p, int s, Variant variant) {
  const bool elastic = allElastic(p);
  if (!validGiven(p, s, variant, elastic)) return 0.0f;
  const int k = int(p.v.size()) - 1;
  const double own = strategyDensity(p, s, variant);
  if (!(own > 0.0)) return 0.0f;
  double sum = 0.0;
  auto add = [&](int i, Variant o) {
    if (!validGiven(p, i, o, elastic)) return;
    const double r = strategyDensity(p, i, o) / own;  // power heuristic, β = 2
    sum += r * r;
  };
  for (int i = 0; i <= k; ++i) {
    add(i, Variant::kStandard);
    add(i, Variant::kOwn);
  }
  if (k >= 2) add(1, Variant::kLightVertex);
  for (int i = 2; i < k; ++i) add(i, Variant::kMollified);
  for (int i = 1; i < k; ++i) {
    add(i, Variant::kMerge);
    add(i, Variant::kMergeOwn);
    add(i, Variant::kMergeMollified);
    add(i, Variant::kBeam);
    add(i, Variant::kBeamOwn);
    add(i, Variant::kPhotonBeam);
    add(i, Variant::kPhotonBeamOwn);
  }
  if (k >= 2) add(k - 1, Variant::kMergeSplat);
  return float(1.0 / sum);
}

}  // namespace kasha::bidir
