#pragma once
// Vertex merging (docs/bdpt-mis.md §12): a light vertex of the pass near camera vertex C[t−1] stands
// for a path that both subpaths reach, x_0 … x_m (the light subpath) … x_k (the camera subpath),
// weighted against every connection and every other merge of that path.
#include <optional>
#include <vector>

#include "integrators/bidirectional/connect.h"
#include "integrators/bidirectional/light_vertex.h"
#include "integrators/bidirectional/photon_beam.h"

namespace kasha::bidir {

// Merges light vertex v with camera vertex C[t−1] (t ≥ 2; η of each kind in c.walk.strategies,
// MergeEta): a shared-family vertex through C[t−1]'s elastic lobe at each lane both reach, an
// own-family one through its fluorescent lobe from v's wavelength to each camera lane's, or through
// its elastic lobe and the wavelength kernel, and at C[1], the camera ray's hit, also through its
// elastic lobe at v's own wavelength, where the sensor responds (Variant::kMergeSplat). The caller
// found v within the pass's radius r (withinRadius), or at C[t−1] the first gather vertex within
// r_g, where only an own vertex merges (through the fluorescent lobe, and at C[1] at its own
// wavelength). Adds each lane's weighted radiance to out[k], and the merges at v's own wavelength
// to `atLight`. With an observer that lays the path out (FullPathLayout: the test oracle recomputes
// the weight over the whole path), `lightPath` must be v's light subpath.
void merge(const Context& c, const std::vector<PathVertex>& C, int t, const LightVertex& v, bool withinRadius,
           float* out, std::vector<SpectralSample>& atLight, const std::vector<PathVertex>* lightPath = nullptr);

// The camera's query beam along C[t−2] → C[t−1] (docs/media-beams.md): from `origin` (C[t−2]) in
// direction w through `medium`, homogeneous, up to `length` (the segment's end, or the first
// index-matched boundary it crosses).
struct QueryBeam {
  Vec3 origin{0.0f}, w{0.0f};
  int medium = -1;
  float length = 0.0f;
  double directionPdf = 0.0;  // C[t−2]'s density of w per unit solid angle (its event's included)
};

// C[t−1]'s query beam, where the walk has beams (MergeEta::beam) and the segment starts in a
// homogeneous medium.
std::optional<QueryBeam> queryBeam(const Context& c, const std::vector<PathVertex>& C, int t);

// Merges light vertex v, a collision in q's medium within its radius of the query beam q at distance
// `along`, with it (Variant::kBeam, kBeamOwn; eq. B3): as merge at a camera collision there
// (C[t−1] stands in for it during the call), with the beam's throughput and densities.
void mergeBeam(const Context& c, std::vector<PathVertex>& C, int t, const QueryBeam& q, float along, const LightVertex& v,
               float* out, const std::vector<PathVertex>* lightPath = nullptr);

// Where a query beam runs through a photon beam's cylinder of radius r (flat-capped at the beam's
// ends, Jarosz et al. 2011's kernel): the chord of the query inside it, up to 2√(r² − g²)/sin θ (g the
// distance of their lines, θ their angle), clipped to the query and to the beam's length, and the
// point a fraction u along it, at t along the query and s along the beam (the merge's vertices). The
// estimate integrates along the chord by that one point, uniform on it: the weights (and, in a
// fluorescent medium, the camera side's T/R_C) change along it.
struct BeamCrossing {
  float t = 0.0f, s = 0.0f, chord = 0.0f;
};
std::optional<BeamCrossing> crossing(const QueryBeam& q, const PhotonBeam& beam, float radius, float u);

// Merges the photon beam with the query beam q of C[t−1] where they cross (Variant::kPhotonBeam,
// kPhotonBeamOwn; docs/media-beams.md eq. B5): the light vertex at x.s on the beam (vertexAlong)
// with a collision at x.t on the query, as mergeBeam, its estimate times the chord over η_pb, the
// cylinder kernel's integral along the query.
void mergePhotonBeam(const Context& c, std::vector<PathVertex>& C, int t, const QueryBeam& q, const PhotonBeam& beam,
                     const BeamCrossing& x, float* out, const std::vector<PathVertex>* lightPath = nullptr);

}  // namespace kasha::bidir
