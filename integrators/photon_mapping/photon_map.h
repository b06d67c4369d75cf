#pragma once
// The photons of one pass with their k-d trees (integrators/point_map.h).
#include "integrators/photon_mapping/photon.h"
#include "integrators/point_map.h"

namespace kasha {

using PhotonMap = PointMap<Photon>;
extern template class PointMap<Photon>;

}  // namespace kasha
