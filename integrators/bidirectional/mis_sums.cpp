#include "integrators/bidirectional/mis_sums.h"

namespace kasha::bidir {

double combine(const MisSums& m, const MisFactors& f) {
  // Without merges their terms are 0, and x + 0 is x: the sums of bdpt and vc do not change.
  const double shared = m.shared + (f.merges ? m.mergeShared : 0.0), own = m.own + (f.merges ? m.mergeOwn : 0.0);
  const double mollified = m.mollified + (f.merges ? m.mergeMollified : 0.0);
  const double ownSplat = m.ownSplat + (f.merges ? m.mergeOwnSplat : 0.0);
  double chosen = f.cameraChoice * f.cameraChoice * m.nee;
  if (f.sharedFamily && f.oneGroup) chosen += f.sharedChoice * f.sharedChoice * shared;
  double sensed = f.laneGain * f.laneGain * (m.hit + chosen);
  double sum = 0.0;
  if (f.ownFamily) {
    const double l2 = f.ownChoice * f.ownChoice;
    sensed += l2 * (own + f.mollifyWidth * f.mollifyWidth * mollified);
    sum += l2 * ownSplat;
  }
  return sum + f.sensorPdf * f.sensorPdf * sensed;
}

MisSums joinMultiplicity(bool connectible, SpectralLobe la, SpectralLobe lb, const Strategies& st) {
  if (!connectible || !st.connections) return {};
  const bool fa = la == SpectralLobe::Fluorescent, fb = lb == SpectralLobe::Fluorescent;
  MisSums m;
  m.shared = 1.0;
  if (fa != fb) m.own = 1.0;
  if (!fa && !fb) m.mollified = 1.0;
  return m;
}

MisSums firstVertexMultiplicity(bool connectible, SpectralLobe lobe, double specCam1, bool finiteLight,
                                const Strategies& st) {
  if (!connectible || !st.connections) return {};
  MisSums m;
  m.nee = specCam1 * specCam1;  // next-event estimation: specCam1·p_NEE, and p_NEE = pL_0
  if (finiteLight && lobe == SpectralLobe::Fluorescent) m.own = 1.0;
  return m;
}

MisSums lightTracingMultiplicity(bool connectible, double specLight, const Strategies& st) {
  if (!connectible || !(specLight > 0.0) || !st.connections) return {};
  MisSums m;
  m.shared = specLight * specLight;
  m.ownSplat = specLight * specLight;
  return m;
}

MisSums directLightMultiplicity(bool seenByPinhole, const Strategies& st) {
  if (!seenByPinhole || !st.connections) return {};
  MisSums m;
  m.shared = 1.0;
  m.ownSplat = 1.0;
  return m;
}

MisSums mergeMultiplicity(bool mergeable, SpectralLobe lobe, double density, bool gather, bool first,
                          const Strategies& st, bool volume, double cameraBeam, double photonBeam) {
  if (!mergeable || !st.merge.any()) return {};
  auto squared = [&](Variant v, bool atGather) {
    const double eta = etaOf(st.merge, v, atGather, volume);
    return (eta * density) * (eta * density);
  };
  MisSums m;
  m.mergeShared = squared(Variant::kMerge, gather);
  if (lobe == SpectralLobe::Fluorescent) {
    m.mergeOwn = squared(Variant::kMergeOwn, gather);
  } else {
    m.mergeMollified = squared(Variant::kMergeMollified, gather);
    if (first) m.mergeOwnSplat = squared(Variant::kMergeSplat, true);
  }
  if (volume && cameraBeam > 0.0) {  // docs/media-beams.md eqs. B2, B4
    const double beam = (squared(Variant::kBeam, false) + squared(Variant::kPhotonBeam, false) * photonBeam * photonBeam) *
                        cameraBeam * cameraBeam;
    m.mergeShared += beam;  // any lobe, as the shared merge's
    if (lobe == SpectralLobe::Fluorescent) m.mergeOwn += beam;
  }
  return m;
}

}  // namespace kasha::bidir
