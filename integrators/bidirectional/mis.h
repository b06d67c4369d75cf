#pragma once
// MIS weights over all strategies of both wavelength families for a full path with
// wavelength-changing vertices (docs/bdpt-mis.md §3–5). The caller lays out the full path x_0 (on a
// light) … x_k (the camera) with, for each vertex, the density with which the light side and the
// camera side would sample it; this module decides which strategies could have produced the path
// and weights by the power heuristic. It recomputes everything from the layout (O(k²) per weight):
// the recursive weights of `integrators/bidirectional/` are tested against it.
#include <vector>

#include "materials/bsdf_model.h"

namespace kasha::bidir {

struct FullVertex {
  // Light-side density of this vertex (from x_{i-1}); x_0: its position's (per sr for a light at
  // infinity): the light choice is a factor of each strategy (cameraChoice, ownChoice).
  double pdfLight = 0.0;
  // Camera-side density (from x_{i+1}); x_{k-1}: the camera direction's (sensorPdf is a factor).
  double pdfCam = 0.0;
  SpectralLobe lobe = SpectralLobe::Elastic;  // interior vertices: the lobe the path uses here
  bool connectible = true;                    // a connection may end here (no delta lobe)
  bool volume = false;                        // a collision in a medium: merges there use MergeEta::volume
  bool mergeable = true;  // connectible, and not a collision whose merge sphere meets a surface (subpath_mis.h)
  // A collision in a homogeneous medium: R_C/F_C, the camera side's probability of flying past it
  // over its density of colliding there, from its camera-side neighbour (docs/media-beams.md eq. B1);
  // 0 elsewhere (no beam strategy there).
  double cameraBeam = 0.0;
  // The same of the light side, R_L/F_L = 1/σ_t (its flights are analog), from its light-side
  // neighbour: with cameraBeam, the photon beams' factor (docs/media-beams.md eq. B4).
  double lightBeam = 0.0;
  double beamSine = 0.0;  // sin θ between its two segments (PathVertex::beamSine)
};

// Which light subpaths a camera sample is combined with (each at most one per camera sample).
struct Families {
  bool shared = false;       // a light subpath at the camera sample's wavelength
  bool independent = false;  // a light subpath at a wavelength of its own (the light-start strategy)
};

// η = N·π r² of the merges (docs/bdpt-mis.md §12), N the light subpaths a camera vertex merges
// against within radius r (0: no merges); `gather`, N·π r_g², that of own merges through a
// fluorescent lobe at the path's first gather vertex (the first non-specular one from the camera),
// which reach light vertices within a radius of their own, r_g, as photon mapping's final gather;
// `volume`, N·(4/3)π r_v³, that of every merge at a collision in a medium, with light vertices in
// media within a sphere of radius r_v (`volumeRadius`), where that sphere meets no surface
// (docs/media.md §6).
struct MergeEta {
  double eta = 0.0, gather = 0.0, volume = 0.0, volumeRadius = 0.0;
  // Whether own vertices merge at the camera's first vertex at their own wavelength
  // (Variant::kMergeSplat): not in a scene with media, where the camera's throughput to that vertex
  // and its density, drawn at the camera's wavelength, would depend on the wavelength too.
  bool splat = true;
  // N·π r_v², that of light vertices in media (photon points) against the camera's query beams (the
  // beam radiance estimate, docs/media-beams.md), at collisions in homogeneous media (0: none).
  double beam = 0.0;
  // N·π r_v²/(2 r_v), that of the light subpaths' flights through homogeneous media (photon beams)
  // against the camera's query beams, with a cylinder kernel of radius r_v around each flight, per
  // unit sin θ of their crossing (0: none; docs/media-beams.md eq. B4).
  double photonBeam = 0.0;
  bool any() const { return eta > 0.0 || gather > 0.0 || volume > 0.0 || beam > 0.0 || photonBeam > 0.0; }
};

struct FullPath {
  std::vector<FullVertex> v;  // x_0 … x_k; v[k] is the camera (pdfCam 1)
  Families families;
  // The factors of the strategies' densities (docs/bdpt-mis.md §5, §10): every strategy but the
  // independent family's t = 1 has the sensor draw the last group's wavelength (sensorPdf); next-event
  // estimation chooses the light with cameraChoice, the shared family's light subpath with
  // sharedChoice, the independent family the light and the first group's wavelength together with
  // ownChoice = p_light(λ_0)·p(light | λ_0).
  double sensorPdf = 0.0;
  double cameraChoice = 0.0;
  double sharedChoice = 0.0;
  double ownChoice = 0.0;
  double specCam1 = 0.0;    // camera-side spectral density of x_1's event (next-event estimation)
  double pdfNee = 0.0;      // next-event density of x_0's position given its light (per sr at infinity)
  bool lightSeenByPinhole = false;  // x_0 may connect to the camera directly (area lights)
  bool lightVertexConnectible = false;  // x_0 is at a finite position (not a light at infinity)
  double specLightLast = 0.0;  // light-side spectral density of x_{k−1}'s event (t = 1 samples it)
  // The camera sample's lanes' gain on the sensor's density of the camera-side and shared strategies
  // (MisFactors::laneGain, docs/bdpt-mis.md §10).
  double laneGain = 1.0;
  // Spectral mollification (independent family, docs/bdpt-mis.md §6): the kernel's effective width
  // ε_h = 1/K_h(0) in nm, which turns a mollified connection's density into one over the path
  // measure; 0: no mollified strategies.
  double mollifyWidth = 0.0;
  // The strategies besides the camera reaching the light (Strategies, mis_sums.h): BDPT's
  // connections, and vertex merging at every connectible interior vertex with η = N·π r² of each
  // kind (0: none).
  bool connections = true;
  MergeEta mergeEta;
};

// Strategies are named by s, the number of light-subpath vertices, and a variant:
// - kStandard: the camera-only strategies (s = 0; s = 1 next-event estimation, where the camera side
//   samples x_1's spectral event and the light point at that wavelength) and the shared family's
//   (2 ≤ s ≤ k − 1 joins, t = 1 for s = k; for k = 1 the light seen by the camera);
// - kOwn: the independent family's joins (2 ≤ s ≤ k − 1, exactly one fluorescent end) and t = 1;
// - kLightVertex: s = 1 through the independent light subpath's own first vertex, x_1's
//   fluorescent lobe evaluated;
// - kMollified: 2 ≤ s ≤ k − 1, two elastic ends whose wavelengths the two sides chose apart,
//   joined through a wavelength kernel (docs/bdpt-mis.md §6);
// - kMerge, kMergeOwn, kMergeMollified: vertex merging at x_s (1 ≤ s ≤ k − 1, both sides sample
//   x_s), with a light subpath of the shared family (a path of one group), of the own family through
//   a fluorescent x_s, or of the own family through an elastic x_s and the wavelength kernel
//   (docs/bdpt-mis.md §12);
// - kMergeSplat: vertex merging at x_{k−1}, the camera ray's hit, of the own family through an
//   elastic x_{k−1}, the sensor at the light vertex's wavelength (no kernel: the camera ray does not
//   depend on λ, so, like t = 1, the light side draws the last group's wavelength), within the
//   gather radius (η_g) (docs/bdpt-mis.md §12);
// - kBeam, kBeamOwn: at a collision x_s in a homogeneous medium, the light side's vertex x_s (a
//   photon point) merged with the camera side's query beam from x_{s+1}, which does not sample where
//   along itself x_s lies (docs/media-beams.md): of the shared family through an elastic x_s, of the
//   own family through a fluorescent one;
// - kPhotonBeam, kPhotonBeamOwn: the same with the light side's flight into x_s (a photon beam) in
//   place of its vertex, which does not sample where along itself x_s lies either.
enum class Variant : uint8_t {
  kStandard, kLightVertex, kMollified, kOwn, kMerge, kMergeOwn, kMergeMollified, kMergeSplat, kBeam, kBeamOwn,
  kPhotonBeam, kPhotonBeamOwn
};

// Whether a variant is a photon beam's.
inline bool isPhotonBeam(Variant v) { return v == Variant::kPhotonBeam || v == Variant::kPhotonBeamOwn; }

// Whether a variant is a beam's: the camera's query beam, against photon points or photon beams.
inline bool isBeam(Variant v) { return v == Variant::kBeam || v == Variant::kBeamOwn || isPhotonBeam(v); }

// Whether a beam variant is the own family's (through a fluorescent x_s).
inline bool isOwnBeam(Variant v) { return v == Variant::kBeamOwn || v == Variant::kPhotonBeamOwn; }

// Whether a variant is one of vertex merging's (beams included).
inline bool isMerge(Variant v) {
  return v == Variant::kMerge || v == Variant::kMergeOwn || v == Variant::kMergeMollified || v == Variant::kMergeSplat ||
         isBeam(v);
}

// η of a merge variant, at the first gather vertex or not (kMergeSplat's x_{k−1} always is one), on a
// surface or at a collision in a medium (`volume`: one η for every variant).
inline double etaOf(const MergeEta& eta, Variant v, bool gather, bool volume) {
  if (isBeam(v)) return volume ? (isPhotonBeam(v) ? eta.photonBeam : eta.beam) : 0.0;
  if (v == Variant::kMergeSplat && !eta.splat) return 0.0;
  if (volume) return eta.volume;
  return v == Variant::kMergeSplat || (v == Variant::kMergeOwn && gather) ? eta.gather : eta.eta;
}

// Weight of strategy (s, variant). Returns 0 if the strategy itself cannot produce the path.
float misWeight(const FullPath& path, int s, Variant variant);

// Whether strategy (s, variant) can produce the path (exposed for tests).
bool strategyValid(const FullPath& path, int s, Variant variant);

}  // namespace kasha::bidir
