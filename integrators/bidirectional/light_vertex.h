#pragma once
// A light subpath's vertex kept for vertex merging (docs/bdpt-mis.md §12): what a merge at a camera
// vertex within the radius needs of the light side — the arriving light's throughput at each lane
// and its direction, and the light side's part of the recursive weights, which does not depend on
// the camera vertex — in kLightVertexBytes.
#include <cstdint>
#include <vector>

#include "integrators/bidirectional/path_vertex.h"

namespace kasha::bidir {

// Lanes a light vertex keeps (vertex merging refuses more per camera sample).
inline constexpr int kLightVertexLanes = 4;

struct LightVertex {
  float p[3];   // position; first, so that PointMap reads positions in place
  // The direction towards the previous vertex, where the light came from, in this vertex's shading
  // frame (as a photon's, photon.h): a merge reads it in the camera vertex's frame.
  float wi[3];
  // Throughput of each lane arriving here (PathVertex::beta; where the subpath ended its lanes on
  // arrival, every lane's that arrived, PathVertex::betaArriving, and lane −1).
  float beta[kLightVertexLanes];
  float lambda;     // the wavelength arriving here where one lane does (PathVertex::lambda)
  float lambda0;    // the subpath's first wavelength (an own subpath's own)
  float ownStart;   // an own subpath's ℓ (its L[0].choicePdf), 0 on a shared one
  float pdfFwd;     // pL_m: this vertex's density on its subpath
  float pdfPrev;    // pL_{m−1}: the previous vertex's
  // The previous vertex's density per unit solid angle at this vertex: |cos θ_{m−1}|/d² (1 at
  // infinity, 0 for a vertex no other strategy samples: a delta light), times a camera path's free
  // flight to it (docs/media.md eq. 9).
  float prevGeometry;
  MisSums sums;     // M_{m−1} + R_m: the light side's sum before the two vertices a merge recomputes
  int16_t light;    // the subpath's light
  uint8_t depth;    // m, this vertex's index on its subpath (1: the first surface)
  int8_t lane;      // PathVertex::lane: −1 every lane, else the one that reaches here
  // kOwn | kElasticBefore | kLanesKept | kPrevConnectible | kPrevFluorescent | kFiniteLight | kMedium |
  // kLightBeam
  uint8_t flags;

  static constexpr uint8_t kOwn = 1, kElasticBefore = 2, kLanesKept = 4, kPrevConnectible = 8, kPrevFluorescent = 16,
                           kFiniteLight = 32, kMedium = 64,
                           // kMedium: a collision in a medium; kLightBeam: one where the light side's beam
                           // ratio is 1/σ_t(lambda) of its medium (PathVertex::lightBeam > 0), else 0
                           kLightBeam = 128;
  bool has(uint8_t flag) const { return (flags & flag) != 0; }
};

inline constexpr size_t kLightVertexBytes = sizeof(LightVertex);
static_assert(kLightVertexBytes == 152);

// Appends a LightVertex for every vertex of light subpath L from index 1 on where a merge can happen
// (mergeable) and a lane carries light; `own` for an own-family subpath.
void keepLightVertices(const std::vector<PathVertex>& L, bool own, const Scene& scene, const Strategies& st,
                       std::vector<LightVertex>& out);

}  // namespace kasha::bidir
