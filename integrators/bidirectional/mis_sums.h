#pragma once
// Running sums for BDPT's recursive MIS weights (docs/bdpt-mis.md §9), in the manner of Georgiev et
// al. 2012 (VCM's partial sums) extended with the wavelength families. The power-heuristic
// denominator of a path is Σ_s' M_s'·P_s'², where P_s' = Π_{i<s'} pL_i · Π_{i≥s'} pC_i is the
// positional part of strategy s' (no light choice in pL_0, no sensor density in pC_{k−1}) and M_s'
// the sum of c² over the variants valid at s' (c: a variant's factor on P_s', such as its spectral
// densities). The factors that depend on the path's wavelengths are applied once the whole path is
// known (docs/bdpt-mis.md §5 and §10):
//
//     M = σ²·(g²·(hit + κ²·nee + S²·[one group]·shared) + ℓ²·(own + ε_h²·mollified)) + ℓ²·ownSplat
//
// σ: the sensor's density of the wavelength reaching the camera; κ: next-event estimation's light
// choice; S: the shared light subpath's; ℓ: the own family's joint density of light and
// wavelength; ε_h the mollification kernel's width; g the lanes' gain (MisFactors::laneGain).
// hit: the camera subpath reaching the light (s' = 0); nee: next-event estimation; shared: the
// shared family's joins and t = 1; own: the own family's joins and light vertex; mollified: its
// mollified joins; ownSplat: its t = 1, the only strategy whose last wavelength the sensor does not
// draw. The merges (§12) are kept apart in mergeShared, mergeOwn, mergeMollified and mergeOwnSplat
// (its merge at x_{k−1} at the light vertex's wavelength; the beams in media, query and photon beams, in the first two), each
// with the factor of its namesake, so
// that the sum without them, the connections alone, is at hand (vcm's pilot, MisFactors::merges).
#include "integrators/bidirectional/mis.h"
#include "materials/bsdf_model.h"

namespace kasha::bidir {

struct MisSums {
  double hit = 0.0, nee = 0.0, shared = 0.0, own = 0.0, mollified = 0.0, ownSplat = 0.0;
  double mergeShared = 0.0, mergeOwn = 0.0, mergeMollified = 0.0, mergeOwnSplat = 0.0;

  MisSums operator+(const MisSums& o) const {
    return {hit + o.hit,
            nee + o.nee,
            shared + o.shared,
            own + o.own,
            mollified + o.mollified,
            ownSplat + o.ownSplat,
            mergeShared + o.mergeShared,
            mergeOwn + o.mergeOwn,
            mergeMollified + o.mergeMollified,
            mergeOwnSplat + o.mergeOwnSplat};
  }
  MisSums operator*(double f) const {
    return {hit * f,         nee * f,          shared * f,         own * f,      mollified * f,
            ownSplat * f,    mergeShared * f,  mergeOwn * f,       mergeMollified * f, mergeOwnSplat * f};
  }
};

// What decides the sums' factors for one full path (and one lane).
struct MisFactors {
  bool sharedFamily = false, ownFamily = false;  // which light subpaths were traced
  double sensorPdf = 0.0;                        // σ = p_sensor(λ_{k−1})
  double cameraChoice = 0.0;                     // κ = next-event estimation's probability of the path's light
  double sharedChoice = 0.0;                     // S = the shared light subpath's probability of it
  double ownChoice = 0.0;                        // ℓ = p_light(λ_0)·p(light | λ_0)
  float lambda0 = 0.0f;                          // λ_0, at which the light's factors are taken
  double mollifyWidth = 0.0;                     // ε_h (0: no mollified joins)
  bool oneGroup = false;                         // every interior vertex is elastic
  // n where every interior vertex keeps the wavelength lanes, else 1: the camera sample's n lanes
  // then sample the path's wavelength with density n·σ for every strategy that has σ
  // (docs/bdpt-mis.md §10); set only in the unified estimator where both families run (with the
  // shared family alone it would cancel; bdpt-independent keeps the weights without it).
  double laneGain = 1.0;
  // Whether the merges' terms count: false gives the sum of the estimator with the connections alone
  // (`vc`'s, in vcm's pilot).
  bool merges = true;
};

// The sum's value for one path.
double combine(const MisSums& m, const MisFactors& f);

// One step of a subpath's recursion (docs/bdpt-mis.md eq. 9): the sum over the strategies with
// fewer vertices on this side, relative to one more vertex, from the one before: r²·(M + R), r the
// other side's density of the vertex over this side's.
inline MisSums extend(const MisSums& before, double ratio, const MisSums& multiplicity) {
  return (multiplicity + before) * (ratio * ratio);
}

// Which strategies an estimator has besides the camera subpath reaching the light
// (docs/bdpt-mis.md §12): BDPT's connections (joins, next-event estimation, the light vertex,
// t = 1), and vertex merging at every connectible interior vertex x_m, whose density is
// Π_{i≤m} pL_i · Π_{i≥m} pC_i · η with η = N·π r² (N light subpaths merged against, r the pass's
// radius; Georgiev et al. 2012 eq. 10's η_VCM with one light subpath per camera sample for the
// connections).
struct Strategies {
  bool connections = true;
  MergeEta merge;
};

// M of the camera subpath reaching the light (s' = 0).
inline MisSums hitMultiplicity() {
  MisSums m;
  m.hit = 1.0;
  return m;
}

// M of a join between two surface vertices with lobes la, lb (2 ≤ s' ≤ k − 1; docs/bdpt-mis.md §4):
// the shared family's (any lobes: the path's single group is checked by `oneGroup`), the own
// family's with exactly one fluorescent end, its mollified one with two elastic ends.
MisSums joinMultiplicity(bool connectible, SpectralLobe la, SpectralLobe lb, const Strategies& st);

// M of next-event estimation and the light-vertex strategy (s' = 1, k ≥ 2): x_1 with lobe `lobe`
// and camera-side spectral density specCam1, the light at a finite position or not.
MisSums firstVertexMultiplicity(bool connectible, SpectralLobe lobe, double specCam1, bool finiteLight,
                                const Strategies& st);

// M of the two light-tracing strategies t = 1 (s' = k ≥ 2): x_{k−1} with the light side's spectral
// density specLight.
MisSums lightTracingMultiplicity(bool connectible, double specLight, const Strategies& st);

// M of the light seen by the camera (k = 1, s' = 1), at the sensor's or the own family's wavelength.
MisSums directLightMultiplicity(bool seenByPinhole, const Strategies& st);

// The merges at vertex x_m with lobe `lobe`, relative to the strategy that has x_m as its last vertex
// on the side that sampled it with density `density` (docs/bdpt-mis.md §12): (η·density)², in the
// shared family's merge part (any lobe: the single group is checked by `oneGroup`) and the own
// family's: exact for a fluorescent lobe (η_g at the first gather vertex), through the wavelength
// kernel (the mollified merge part) for an elastic one, and at x_{k−1} also exact at the light
// vertex's wavelength (Variant::kMergeSplat, η_g, in the merge part whose last wavelength the sensor
// does not draw).
// `gather`: x_m is the path's first gather vertex (MergeEta); `first`: x_m is x_{k−1}, the camera
// ray's hit; `volume`: x_m is a collision in a medium (every merge there with η_v). There the beams
// (Variant::kBeam, kBeamOwn) add (η_b·density·cameraBeam)² to the merge part of their namesake
// (FullVertex::cameraBeam; docs/media-beams.md eq. B2), which has their factors, and the photon beams
// (Variant::kPhotonBeam, kPhotonBeamOwn) (η_pb·density·cameraBeam·lightBeam·sin θ)² (eq. B4), with
// photonBeam = lightBeam·sin θ (photonBeamRatio).
MisSums mergeMultiplicity(bool mergeable, SpectralLobe lobe, double density, bool gather, bool first,
                          const Strategies& st, bool volume = false, double cameraBeam = 0.0, double photonBeam = 0.0);

// A photon beam's factor at a collision besides the query beam's: R_L/F_L·sin θ (eq. B4).
inline double photonBeamRatio(double lightBeam, double beamSine) { return lightBeam * beamSine; }

}  // namespace kasha::bidir
