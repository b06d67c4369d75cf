#include "integrators/bdpt/mis_sums.h"

namespace kasha::bdpt {

double combine(const MisSums& m, const MisFactors& f) {
  double sum = m.base;
  if (f.ownFamily) sum += f.lightPdf * f.lightPdf * (m.own + f.mollifyWidth * f.mollifyWidth * m.mollified);
  if (f.sharedFamily && f.oneGroup) sum += m.shared;
  return sum;
}

MisSums joinMultiplicity(bool connectible, SpectralLobe la, SpectralLobe lb) {
  if (!connectible) return {};
  const bool fa = la == SpectralLobe::Fluorescent, fb = lb == SpectralLobe::Fluorescent;
  MisSums m;
  m.shared = 1.0;
  if (fa != fb) m.own = 1.0;
  if (!fa && !fb) m.mollified = 1.0;
  return m;
}

MisSums firstVertexMultiplicity(bool connectible, SpectralLobe lobe, double specCam1, bool finiteLight) {
  if (!connectible) return {};
  MisSums m;
  m.base = specCam1 * specCam1;  // next-event estimation: specCam1·p_NEE, and p_NEE = pL_0
  if (finiteLight && lobe == SpectralLobe::Fluorescent) m.own = 1.0;
  return m;
}

MisSums lightTracingMultiplicity(bool connectible, double specLight, double sensorPdf) {
  if (!connectible || !(specLight > 0.0)) return {};
  MisSums m;
  m.own = specLight * specLight;
  m.shared = sensorPdf * sensorPdf * specLight * specLight;
  return m;
}

MisSums directLightMultiplicity(bool seenByPinhole, double sensorPdf) {
  if (!seenByPinhole) return {};
  MisSums m;
  m.own = 1.0;
  m.shared = sensorPdf * sensorPdf;
  return m;
}

}  // namespace kasha::bdpt
