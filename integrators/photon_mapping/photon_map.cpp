#include "integrators/photon_mapping/photon_map.h"

#include "integrators/point_map_impl.h"

namespace kasha {

template class PointMap<Photon>;

}  // namespace kasha
