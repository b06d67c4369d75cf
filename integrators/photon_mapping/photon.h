#pragma once
// A photon: a vertex of a light subpath kept for density estimation (Jensen 1996; Hachisuka &
// Jensen 2009). Each photon carries its own wavelength (transport.md §4).
#include <cstddef>
#include <cstdint>

namespace kasha {

struct Photon {
  float p[3];      // position; first, so that FLANN reads positions in place with stride sizeof(Photon)
  float wi[3];     // unit direction towards where the light came from, in the frame of the surface the
                   // photon landed on (its Bsdf's local, shading frame)
  float lambda;    // wavelength of the light arriving here, nm
  float power;     // the light subpath's throughput: flux per emitted subpath, per nm of wavelength
                   // density already divided out (the light tracer's beta), times |ω_i·n_s|/|ω_i·n_g|
                   // here (1 without a shading normal: Veach's f_s, docs/photon-mapping.md §3)
  uint32_t depth;  // index of this vertex on its light subpath: 1 for the first surface hit
};
static_assert(sizeof(Photon) == 36);

// Leaf size of FLANN's single k-d tree (KDTreeSingleIndexParams).
inline constexpr int kPhotonLeafSize = 10;

// Memory per stored photon (docs/photon-mapping.md): the record and FLANN's index over it, which
// holds a reordered copy of the positions (12 bytes), a row pointer (8) and an int permutation
// entry (4) per point, and at most about 4/leafSize tree nodes of 40 bytes per point.
inline constexpr size_t kIndexBytesPerPhoton = 12 + 8 + 4 + 4 * 40 / kPhotonLeafSize;
inline constexpr size_t kBytesPerPhoton = sizeof(Photon) + kIndexBytesPerPhoton;
static_assert(kBytesPerPhoton == 76);

}  // namespace kasha
