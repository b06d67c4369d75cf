#include "integrators/bidirectional/pilot_observer.h"

#include <limits>

#include "integrators/bidirectional/connect.h"

namespace kasha::bidir {

double densityOverAlone(Alone which, const MisSums& total, const MisFactors& f, double sum, double ownAloneChoice) {
  MisFactors alone = f;
  switch (which) {
    case Alone::Camera: alone.ownFamily = alone.sharedFamily = false; break;
    case Alone::Shared:
      alone.ownFamily = false;
      alone.sharedChoice = f.cameraChoice;
      break;
    case Alone::Own:
      alone.sharedFamily = false;
      alone.ownChoice = ownAloneChoice;
      break;
    case Alone::Connections:  // vc: no merges, and no wavelength kernel (no mollified joins)
      alone.merges = false;
      alone.mollifyWidth = 0.0;
      break;
  }
  const double a = combine(total, alone);
  return a > 0.0 ? std::sqrt(sum / a) : std::numeric_limits<double>::infinity();
}

void PilotObserver::onWeight(const WeightEvent& e) {
  MergeWeightCount::onWeight(e);
  const MisFactors& f = e.factors;
  const float w = e.weight;
  // ℓ of the own family alone, bdpt-independent's light subpath: its wavelength from the
  // light-start strategy, its light as next-event estimation's; only the merged light subpath's
  // start (§11) differs from it.
  const WalkSettings& walk = e.c.walk;
  const double ownAlone =
      f.ownFamily && walk.lightFirst ? double(walk.lightWavelengths->pdf(f.lambda0)) * f.cameraChoice : 0.0;
  PilotMoments::Alternative* a = moments_.alone;
  const bool shared = w > 0.0f && !f.oneGroup && f.sensorPdf > 0.0 && f.cameraChoice > 0.0;
  a[int(Alone::Shared)].pending = shared ? densityOverAlone(Alone::Shared, e.total, f, e.sum, ownAlone) : 1.0;
  a[int(Alone::Own)].pending = w > 0.0f ? densityOverAlone(Alone::Own, e.total, f, e.sum, ownAlone) : 1.0;
  const bool sensed = w > 0.0f && f.sensorPdf > 0.0 && f.cameraChoice > 0.0;
  a[int(Alone::Camera)].pending = sensed ? densityOverAlone(Alone::Camera, e.total, f, e.sum, ownAlone) : 1.0;
  // Without merges (bdpt's pilot) the connections alone are the estimator itself: ρ = 1.
  const bool merges = w > 0.0f && e.c.walk.strategies.merge.any();
  a[int(Alone::Connections)].pending = merges ? densityOverAlone(Alone::Connections, e.total, f, e.sum, ownAlone) : 1.0;
}

}  // namespace kasha::bidir
