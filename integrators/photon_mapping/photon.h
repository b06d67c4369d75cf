#pragma once
// A photon: a vertex of a light subpath kept for density estimation (Jensen 1996; Hachisuka &
// Jensen 2009). The subpath carries wavelength lanes (hero wavelengths, as the light tracer's), so a
// photon holds the lanes that arrive at its vertex, each with its own wavelength and flux
// (docs/transport.md §4; docs/photon-mapping.md §2): up to kPhotonLanes in one cache line, more as
// several photons at the same vertex (the estimate sums over lanes, so the split changes nothing).
#include <algorithm>
#include <cstddef>
#include <cstdint>

#include "integrators/point_map.h"

namespace kasha {

inline constexpr int kPhotonLanes = 4;

struct alignas(64) Photon {
  float p[3];      // position; first, so that FLANN reads positions in place with stride sizeof(Photon)
  float wi[3];     // unit direction towards where the light came from, in the frame of the surface the
                   // photon landed on (its Bsdf's local, shading frame); in world space for a volume photon
  uint16_t lanes;  // lanes held, 1 to kPhotonLanes
  uint16_t depth;  // index of this vertex on its light subpath: 1 for its first surface hit or collision
  bool inMedium;   // a collision in a medium (the volume photon map's), not a surface
  float lambda[kPhotonLanes];  // each lane's wavelength of the light arriving here, nm
  float power[kPhotonLanes];   // each lane's throughput: flux per emitted subpath, per nm of wavelength
                               // density already divided out, with the lane's hero weight (the light
                               // tracer's beta, times the free flights' lane MIS), times |ω_i·n_s|/|ω_i·n_g|
                               // here (1 without a shading normal and in a medium: Veach's f_s,
                               // docs/photon-mapping.md §3)
};
static_assert(sizeof(Photon) == 64);

// Photons stored for a vertex that `lanes` lanes reach.
constexpr size_t photonsPerVertex(int lanes) { return size_t((lanes + kPhotonLanes - 1) / kPhotonLanes); }

// Memory of FLANN's index per photon (docs/photon-mapping.md §5): a reordered copy of the positions
// (12 bytes), a row pointer (8) and an int permutation entry (4) per point, and at most about
// 4/leafSize tree nodes of 40 bytes per point.
inline constexpr size_t kIndexBytesPerPhoton = 12 + 8 + 4 + 4 * 40 / kPointLeafSize;
// Peak memory per stored photon: the larger of the record with FLANN's index (64 + 30) and the
// moment the pass's per-chunk buffers are copied into one array (two records).
inline constexpr size_t kBytesPerPhoton = std::max(2 * sizeof(Photon), sizeof(Photon) + kIndexBytesPerPhoton);
static_assert(kBytesPerPhoton == 128);

}  // namespace kasha
