#pragma once
// Vertex merging (docs/bdpt-mis.md §12): a light vertex of the pass near camera vertex C[t−1] stands
// for a path that both subpaths reach, x_0 … x_m (the light subpath) … x_k (the camera subpath),
// weighted against every connection and every other merge of that path.
#include <vector>

#include "integrators/bidirectional/connect.h"
#include "integrators/bidirectional/light_vertex.h"

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

}  // namespace kasha::bidir
