#pragma once
// The contributions of BDPT's strategies, each with its MIS weight (docs/bdpt-mis.md §3).
#include <optional>
#include <vector>

#include "scene/scene.h"
#include "core/wavelength_density.h"
#include "integrators/bidirectional/mis.h"
#include "integrators/bidirectional/mis_observer.h"
#include "integrators/bidirectional/path_vertex.h"
#include "integrators/bidirectional/subpaths.h"

namespace kasha::bidir {

// The camera's view of a light-subpath vertex (t = 1): where it projects through a lens point and
// the camera's density of it; the same for both views at a common vertex.
struct CameraLink {
  std::optional<Camera::Connection> connection;
  double pdfCam = 0.0;  // the camera's area density of the vertex (whole film)
};

// Visibility between light-subpath vertex s−1 and camera-subpath vertex t−1 (t = 1: the pinhole),
// and vertex s−1's camera link, kept for the merged light subpath's second view, whose vertex s−1
// is the same point while the two views share their vertices (docs/bdpt-mis.md §11): one shadow
// ray and one projection onto the film serve both families there.
class VisibilityMemo {
 public:
  // Forgets everything; keeps s up to sharedVertices, t up to cameraVertices.
  void reset(int sharedVertices, int cameraVertices) {
    shared_ = sharedVertices;
    stride_ = cameraVertices + 1;
    known_.assign(size_t((sharedVertices + 1) * stride_), int8_t(-1));
    links_.assign(size_t(sharedVertices + 1), std::nullopt);
  }
  // The remembered answer for (s, t), or test()'s (remembered where s ≤ sharedVertices).
  template <class Test>
  bool get(int s, int t, Test&& test) {
    if (s > shared_) return test();
    int8_t& k = known_[size_t(s * stride_ + t)];
    if (k < 0) k = test() ? 1 : 0;
    return k == 1;
  }
  // The remembered camera link of vertex s − 1, or make()'s (remembered where s ≤ sharedVertices).
  template <class Make>
  CameraLink link(int s, Make&& make) {
    if (s > shared_) return make();
    std::optional<CameraLink>& l = links_[size_t(s)];
    if (!l) l = make();
    return *l;
  }

 private:
  std::vector<int8_t> known_;
  std::vector<std::optional<CameraLink>> links_;
  int shared_ = 0, stride_ = 0;
};

struct Context {
  const Scene& scene;
  const WalkSettings& walk;
  Families families;    // the light subpaths traced with each camera subpath
  // The camera sample's wavelength lanes (docs/bdpt-mis.md §10); each lane has its own weights.
  const Lanes& lanes;
  const WavelengthDensity& sensor;  // the sensor's density, for other wavelengths' densities
  RayCounter& counter;
  // Spectral mollification (Independent only): the wavelength kernel's half-width h of this
  // pass in nm; 0 for none (docs/bdpt-mis.md §6).
  float bandwidth = 0.0f;
  // The camera sample's pixel, where strategies with t ≥ 2 report their contributions to the observer.
  Vec2 pixel{0.0f};
  // Whether t = 1 splats keep each lane's wavelength (for spectral bins), or sum the lanes' XYZ.
  bool spectralSplats = false;
  // Per light, the XYZ of an area emitter seen directly (integrators/direct_emission.h): s = 0, t = 2
  // adds it exactly with weight 1, and the light vertex seen by the camera gets weight 0; null to
  // weigh the two as usual. Only with lanes (the shared family alone) and no spectral bins.
  const std::vector<Vec3>* directXyz = nullptr;

  // The merged light subpath (docs/bdpt-mis.md §11): how many leading vertices its two views share
  // (traceMergedLightSubpath); 0 where the light subpaths are separate.
  int sharedLightVertices = 0;

  // What watches the weights and contributions (mis_observer.h: the test oracle, the per-strategy
  // images, a pilot); null in a render that asks for none of them.
  MisObserver* observer = nullptr;
};

// Strategies with t ≥ 2 add each lane's radiance at its camera wavelength, weighted, to out[k].
// s = 0: the camera subpath's vertex C[t−1] lies on an emitter (an area emitter seen directly adds
// its exact XYZ to `xyz` where c.directXyz is set).
void emitterHit(const Context& c, const std::vector<PathVertex>& C, int t, float* out, Vec3& xyz);
// s = 1: next-event estimation from C[t−1] at the wavelength its spectral event chose.
void nextEvent(const Context& c, const std::vector<PathVertex>& C, int t, Sampler& rng, float* out);
// s = 1 through the own-family light subpath's vertex L[0]: its wavelength, drawn from the
// light-start strategy, reaches the camera's through C[t−1]'s fluorescent lobe.
void connectLightVertex(const Context& c, const std::vector<PathVertex>& L, const std::vector<PathVertex>& C, int t,
                        float* out);
// s ≥ 2, t ≥ 2: connect L[s−1] of a light subpath of `family` and C[t−1] through every exact lobe
// pair (two elastic lobes in the shared family, one fluorescent in the own), and through two
// elastic lobes with the wavelength kernel when mollifying (own family).
// With `memo`, visibility is remembered for the other view of a merged light subpath.
void connect(const Context& c, const std::vector<PathVertex>& L, LightFamily family, int s,
             const std::vector<PathVertex>& C, int t, float* out, VisibilityMemo* memo = nullptr);
// t = 1: L[s−1] (s ≥ 1) of a light subpath of `family` seen by the camera through the lens point
// lensSample picks (Camera::connect), with the spectral event the light subpath sampled there;
// appends a splat (film units) per lane if visible. With `memo`, a common vertex keeps the first
// view's lens point.
void connectToCamera(const Context& c, const std::vector<PathVertex>& L, LightFamily family, int s, Vec2 lensSample,
                     std::vector<Splat>& splats, VisibilityMemo* memo = nullptr);

// Every strategy of one camera sample: the camera subpath C joined to the light subpaths of the
// shared (LS) and own (LO) families (either may be empty). Sets out[k] to lane k's radiance at its
// camera wavelength (weighted, t ≥ 2) and xyz to what is added as XYZ, and appends the t = 1 splats.
void connectSubpaths(const Context& c, const std::vector<PathVertex>& C, const std::vector<PathVertex>& LS,
                     const std::vector<PathVertex>& LO, Sampler& rng, std::vector<Splat>& splats, float* out,
                     Vec3& xyz);

}  // namespace kasha::bidir
