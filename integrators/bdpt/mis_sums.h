#pragma once
// Running sums for BDPT's recursive MIS weights (docs/bdpt-mis.md §9), in the manner of Georgiev et
// al. 2012 (VCM's partial sums) extended with the wavelength families. The power-heuristic
// denominator of a path is Σ_s' M_s'·P_s'², where P_s' = Π_{i<s'} pL_i · Π_{i≥s'} pC_i is the
// positional part of strategy s' and M_s' the sum of c² over the variants valid at s' (c: a
// variant's factor on P_s', such as its wavelength densities). M splits by what decides the
// variants' factors and validity only once the whole path is known:
//
//     M = base + p_light(λ_0)²·(own + ε_h²·mollified) + [path has one group]·shared
//
// base: the camera-only strategies (s' = 0, next-event estimation); own: the own-wavelength
// family's; mollified: its mollified joins (ε_h the kernel's width); shared: the shared family's.
#include "materials/bsdf_model.h"

namespace kasha::bdpt {

struct MisSums {
  double base = 0.0, own = 0.0, mollified = 0.0, shared = 0.0;

  MisSums operator+(const MisSums& o) const {
    return {base + o.base, own + o.own, mollified + o.mollified, shared + o.shared};
  }
  MisSums operator*(double f) const { return {base * f, own * f, mollified * f, shared * f}; }
};

// What decides the split's factors for one full path.
struct MisFactors {
  bool sharedFamily = false, ownFamily = false;  // which light subpaths were traced
  double lightPdf = 0.0;                         // p_light(λ_0)
  double mollifyWidth = 0.0;                     // ε_h (0: no mollified joins)
  bool oneGroup = false;                         // every interior vertex is elastic
};

// The sum's value for one path.
double combine(const MisSums& m, const MisFactors& f);

// One step of a subpath's recursion (docs/bdpt-mis.md eq. 9): the sum over the strategies with
// fewer vertices on this side, relative to one more vertex, from the one before: r²·(M + R), r the
// other side's density of the vertex over this side's.
inline MisSums extend(const MisSums& before, double ratio, const MisSums& multiplicity) {
  return (multiplicity + before) * (ratio * ratio);
}

// M of a join between two surface vertices with lobes la, lb (2 ≤ s' ≤ k − 1; docs/bdpt-mis.md §4):
// the shared family's (any lobes: the path's single group is checked by `oneGroup`), the own
// family's with exactly one fluorescent end, its mollified one with two elastic ends.
MisSums joinMultiplicity(bool connectible, SpectralLobe la, SpectralLobe lb);

// M of next-event estimation and the light-vertex strategy (s' = 1, k ≥ 2): x_1 with lobe `lobe`
// and camera-side spectral density specCam1, the light at a finite position or not.
MisSums firstVertexMultiplicity(bool connectible, SpectralLobe lobe, double specCam1, bool finiteLight);

// M of the two light-tracing strategies t = 1 (s' = k ≥ 2): x_{k−1} with the light side's spectral
// density specLight; the shared one's wavelength drawn by the sensor with density sensorPdf.
MisSums lightTracingMultiplicity(bool connectible, double specLight, double sensorPdf);

// M of the light seen by the camera (k = 1, s' = 1).
MisSums directLightMultiplicity(bool seenByPinhole, double sensorPdf);

}  // namespace kasha::bdpt
