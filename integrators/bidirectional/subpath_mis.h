#pragma once
// The recursive MIS weights' per-subpath part (docs/bdpt-mis.md §9): each vertex stores the running
// sum R over the strategies with at least two fewer vertices on its side, so that a connection
// completes its weight from the two vertices next to it in O(1).
#include <vector>

#include "integrators/bidirectional/mis_sums.h"
#include "integrators/bidirectional/path_vertex.h"

namespace kasha::bidir {

// Other side's density over own side's; 0 where the own side's is 0.
inline double densityRatio(double other, double own) { return own > 0.0 ? other / own : 0.0; }

// M of the strategy s' = j (j vertices on the light subpath L, the last of them L[j − 1]) with L[j]
// using `lobe` and sending `lambdaOut` on (the connection's event there, or its own sampled one),
// together with the merges at L[j] (docs/bdpt-mis.md §12: a side's strategy s' carries the merges at
// the vertex that side sampled last). `gather`: L[j] connects to the camera (t = 1), so it is
// x_{k−1}, the path's first gather vertex (MergeEta) and the camera ray's hit (Variant::kMergeSplat).
// `ends`: the path being weighed ends a connection at L[j] (PathVertex::joinable); L[j − 1] is
// always inside it. cameraBeam: the camera side's beam ratio at L[j] (PathVertex::cameraBeam) over
// the segment by which the path's camera side reaches it; beamSine, sin θ between that segment and
// L[j]'s arrival (PathVertex::beamSine).
MisSums lightMultiplicity(const std::vector<PathVertex>& L, int j, SpectralLobe lobe, float lambdaOut,
                          const Strategies& st, bool gather, bool ends, double cameraBeam, double beamSine);
// The same with L[j]'s own sampled event, reached by the camera side from L[j + 1].
MisSums lightMultiplicity(const std::vector<PathVertex>& L, int j, const Strategies& st, bool gather, bool ends);

// M of the strategy with j vertices on the camera subpath C (t' = j, s' = k + 1 − j), C[j] using
// `lobe` with `lambdaIn` arriving from the light side, together with the merges at C[j]; `ends` as
// for lightMultiplicity. lightBeam: the light side's beam ratio at C[j] (PathVertex::lightBeam) over
// the segment by which the path's light side reaches it; beamSine as for lightMultiplicity.
MisSums cameraMultiplicity(const std::vector<PathVertex>& C, int j, SpectralLobe lobe, float lambdaIn,
                           const Strategies& st, bool ends, double lightBeam, double beamSine);
// The same with C[j]'s own sampled event, reached by the light side from C[j + 1].
MisSums cameraMultiplicity(const std::vector<PathVertex>& C, int j, const Strategies& st, bool ends);

// Whether a merge can happen at v on the path being weighed: a surface without a delta lobe, or a
// collision in a medium whose merge sphere meets no surface; `ends` as for PathVertex::joinable.
inline bool mergeable(const PathVertex& v, bool ends) { return v.scatters() && v.joinable(ends) && v.sphereInMedium; }

// Sets the running sum and the elastic flag of the subpath's newest vertex (Radiance: a camera
// subpath, Importance: a light subpath). Called once per vertex, in order, once the vertex two
// before has its reverse density.
void updateSums(std::vector<PathVertex>& path, TransportMode mode, const Strategies& st);

// R_n of one side at a connection through its vertex v_{n−1} (docs/bdpt-mis.md eq. 10): from the
// sum stored at v_{n−1}, the ratio and M recomputed at v_{n−2} and at v_{n−1}.
inline MisSums sideSum(const MisSums& stored, double ratioBefore, const MisSums& before, double ratioLast,
                       const MisSums& last) {
  return extend(extend(stored, ratioBefore, before), ratioLast, last);
}

}  // namespace kasha::bidir
