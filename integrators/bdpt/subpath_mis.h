#pragma once
// The recursive MIS weights' per-subpath part (docs/bdpt-mis.md §9): each vertex stores the running
// sum R over the strategies with at least two fewer vertices on its side, so that a connection
// completes its weight from the two vertices next to it in O(1).
#include <vector>

#include "integrators/bdpt/mis_sums.h"
#include "integrators/bdpt/path_vertex.h"

namespace kasha::bdpt {

// Other side's density over own side's; 0 where the own side's is 0.
inline double densityRatio(double other, double own) { return own > 0.0 ? other / own : 0.0; }

// M of the strategy with j vertices on the light subpath L (s' = j), the last of them, L[j], using
// `lobe` and sending `lambdaOut` on (the connection's event there, or its own sampled one).
MisSums lightMultiplicity(const std::vector<PathVertex>& L, int j, SpectralLobe lobe, float lambdaOut);
// The same with L[j]'s own sampled event.
MisSums lightMultiplicity(const std::vector<PathVertex>& L, int j);

// M of the strategy with j vertices on the camera subpath C (t' = j, s' = k + 1 − j), C[j] using
// `lobe` with `lambdaIn` arriving from the light side.
MisSums cameraMultiplicity(const std::vector<PathVertex>& C, int j, SpectralLobe lobe, float lambdaIn);
// The same with C[j]'s own sampled event.
MisSums cameraMultiplicity(const std::vector<PathVertex>& C, int j);

// Sets the running sum and the elastic flag of the subpath's newest vertex (Radiance: a camera
// subpath, Importance: a light subpath). Called once per vertex, in order, once the vertex two
// before has its reverse density.
void updateSums(std::vector<PathVertex>& path, TransportMode mode);

// R_n of one side at a connection through its vertex v_{n−1} (docs/bdpt-mis.md eq. 10): from the
// sum stored at v_{n−1}, the ratio and M recomputed at v_{n−2} and at v_{n−1}.
inline MisSums sideSum(const MisSums& stored, double ratioBefore, const MisSums& before, double ratioLast,
                       const MisSums& last) {
  return extend(extend(stored, ratioBefore, before), ratioLast, last);
}

}  // namespace kasha::bdpt
