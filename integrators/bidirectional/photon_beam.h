#pragma once
// A light subpath's flight through a homogeneous medium kept as a photon beam (Jarosz et al. 2011;
// docs/media-beams.md eqs. B4, B5): every point along it stands for a collision the flight could
// have made there, a light vertex whose light-side densities and sums depend on where along the
// beam it lies. The record keeps what does not (the flight's throughput, its origin's direction
// density, the light side's sums before the origin's beam term), so that `vertexAlong` makes the
// light vertex at any distance in O(1), as the light subpath would have kept it (keepLightVertices).
#include <vector>

#include "integrators/bidirectional/light_vertex.h"

namespace kasha::bidir {

struct PhotonBeam {
  Vec3 origin{0.0f}, w{0.0f};  // the flight from its origin vertex, x_{m−1}, in direction w
  float length = 0.0f;         // up to the vertex it reached, x_m
  int medium = -1;
  // x_{m−1}'s density of w per unit solid angle, its event included.
  double directionPdf = 0.0;
  // x_{m−1} as the camera side reaches it: a collision in a medium (and which), or a point with a
  // normal (zero: none) that a delta light makes unreachable.
  bool originInMedium = false, originDelta = false;
  int originMedium = -1;
  Vec3 originNormal{0.0f};
  // The light vertex x_m at a collision along the beam, but for what depends on where: its position
  // and direction, densities (pdfFwd, prevGeometry) and sums, which vertexAlong sets.
  LightVertex vertex{};
  // The sums' part that does not depend on where (x_m's stored sum and x_{m−1}'s multiplicity without
  // its query beam), and the part x_{m−1}'s query beam adds per (R_C/F_C)² at x_{m−1} (eq. B2), which
  // does: the camera side reaches x_{m−1} from x_m.
  MisSums sumsFixed, sumsPerOriginBeam;
};

// Appends a PhotonBeam for every flight of light subpath L (`own` for an own-family one) that runs
// through a homogeneous medium from a vertex at a finite position without crossing a boundary, where
// the walk has photon beams (MergeEta::photonBeam) and lane 0 carries light.
void keepPhotonBeams(const std::vector<PathVertex>& L, bool own, const Scene& scene, const Strategies& st,
                     std::vector<PhotonBeam>& out);

// The light vertex at a collision at distance s along the beam (0 < s ≤ length): as the flight would
// have made it, with the beam's throughput (T/R_L = 1 of an analog flight: the beam's own); and the
// camera side's R_C/F_C at the beam's origin, reached from it (its sums hold that term).
struct BeamPoint {
  LightVertex vertex;
  double originCameraBeam = 0.0;
};
BeamPoint vertexAlong(const Scene& scene, const PhotonBeam& beam, float s);

}  // namespace kasha::bidir
