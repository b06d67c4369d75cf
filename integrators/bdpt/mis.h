#pragma once
// MIS weights over all (s, t) strategies for a full path with wavelength-changing vertices
// (docs/bdpt-mis.md §3–4). The caller lays out the full path x_0 (on a light) … x_k (the camera)
// with, for each vertex, the density with which the light side and the camera side would sample
// it; this module decides which strategies could have produced the path and weights by the
// power heuristic.
#include <vector>

#include "integrators/bdpt/subpaths.h"

namespace kasha::bdpt {

struct FullVertex {
  double pdfLight = 0.0;  // light-side density of this vertex (from x_{i-1}; x_0: light and wavelength choice)
  double pdfCam = 0.0;    // camera-side density (from x_{i+1}; x_{k-1}: camera direction [× sensor])
  SpectralLobe lobe = SpectralLobe::Elastic;  // interior vertices: the lobe the path uses here
  bool connectible = true;                    // a connection may end here (no delta lobe)
};

struct FullPath {
  std::vector<FullVertex> v;  // x_0 … x_k; v[k] is the camera (pdfCam 1)
  WavelengthMode mode = WavelengthMode::Independent;
  double specCam1 = 0.0;    // camera-side spectral density of x_1's event (next-event estimation)
  double pdfNee = 0.0;      // next-event density of x_0 given λ_0: p(light | λ_0)·p_A (per sr at infinity)
  bool lightSeenByPinhole = false;  // x_0 may connect to the camera directly (area lights)
  bool lightVertexConnectible = false;  // x_0 is at a finite position (not a light at infinity)
  double specLightLast = 0.0;  // light-side spectral density of x_{k−1}'s event (t = 1 samples it)
  // Spectral mollification (Independent only, docs/bdpt-mis.md §6): the kernel's effective width
  // ε_h = 1/K_h(0) in nm, which turns a mollified connection's density into one over the path
  // measure; 0: no mollified strategies.
  double mollifyWidth = 0.0;
};

// Strategies are named by s, the number of light-subpath vertices, and a variant. For s = 1 when
// k ≥ 2 there are two: next-event estimation (kStandard: the camera side samples x_1's spectral
// event and the light point at that wavelength) and the light subpath's own first vertex
// (kLightVertex: its wavelength from the lights' power spectrum, x_1's fluorescent lobe
// evaluated). For 2 ≤ s ≤ k − 1, kMollified joins two elastic connection vertices whose
// wavelengths were chosen independently through a wavelength kernel (docs/bdpt-mis.md §6).
enum class Variant : uint8_t { kStandard, kLightVertex, kMollified };

// Weight of strategy s (for k = 1, s = 1 is the light seen by the camera). Returns 0 if the
// strategy itself cannot produce the path.
float misWeight(const FullPath& path, int s, Variant variant = Variant::kStandard);

// Whether strategy s can produce the path (exposed for tests).
bool strategyValid(const FullPath& path, int s, Variant variant = Variant::kStandard);

}  // namespace kasha::bdpt
