#pragma once
// Camera and light subpaths for BDPT (docs/bdpt-mis.md §2).
#include <vector>

#include "core/sampler.h"
#include "scene/scene.h"
#include "core/wavelength_density.h"
#include "integrators/bidirectional/light_first.h"
#include "integrators/bidirectional/mis.h"
#include "integrators/bidirectional/path_vertex.h"
#include "integrators/integrator.h"

namespace kasha::bidir {

// Which light subpaths BDPT combines with each camera subpath: the two exact wavelength families of
// docs/transport.md §3 alone, or both (docs/bdpt-mis.md §5).
enum class WavelengthMode : uint8_t {
  Shared,       // the light subpath starts at the camera sample's wavelength
  Independent,  // the light subpath draws its own wavelength from the light-start strategy
  Unified,      // both: in scenes that fluoresce, one light subpath read as both (docs/bdpt-mis.md §11)
};

// The wavelength of one light subpath.
enum class LightFamily : uint8_t {
  Shared,  // the camera sample's; the subpath stops at its first fluorescent event
  Own,     // drawn with the light from the light-start strategy
};

// The light subpaths of each camera sample (docs/bdpt-mis.md §5): the unified estimator traces an
// own-wavelength one only where some path can fluoresce, since on elastic paths the shared family
// has every strategy the own one has.
Families familiesFor(const Scene& scene, WavelengthMode mode);

struct WalkSettings {
  int maxDepth = 64;  // maximum number of scattering vertices on a full path
  int rrDepth = 3;
  const WavelengthDensity* lightWavelengths = nullptr;  // the light-start strategy's density (own family)
  // Set where the unified estimator merges both families into one light subpath (docs/bdpt-mis.md
  // §11): how that subpath starts.
  const LightFirstStart* lightFirst = nullptr;
  // The strategies the weights count (mis_sums.h): BDPT's connections, and vertex merging in vcm.
  Strategies strategies;
  bool hideEmitters = false;  // RenderSettings::hideEmitters: no path without a scattering vertex
};

// What a camera sample's lanes point into (Lanes::lights, Lanes::ownStart).
struct LaneTables {
  LaneLightTable lights;
  std::vector<float> ownStart;
};

// The camera sample's n lanes from one uniform u: lane k at the stratum (u + k/n) of the sensor
// density's inverse CDF (pt's lanes, Wilkie et al. 2014), each with its density and response;
// with more than one, `tables` is filled with the lights' powers at them, and given the merged
// subpath's start `merged`, its density Q(l)·p_l at each lane for each light, else given the own
// family's light-start density `own` (where that family runs), each lane's density under it. The
// lanes point into `tables`.
Lanes sensorLanes(const Scene& scene, const WavelengthDensity& sensor, float u, int n, LaneTables& tables,
                  const WavelengthDensity* own = nullptr, const LightFirstStart* merged = nullptr);

// The light chosen with u for the lanes (a lane's wavelength at random, then ∝ Φ_l there: the
// mixture over the lanes, LaneLightTable; with one lane, ∝ Φ_l(λ)) and its probability.
std::pair<size_t, float> selectLight(const Scene& scene, const Lanes& lanes, float u);
// C[0] is the pinhole; C[1] the first hit. The lanes are the sensor's wavelengths; C[1].pdfFwd is
// the camera direction's density alone (the sensor's is a factor of the weights, mis_sums.h).
void traceCameraSubpath(const Scene& scene, Vec2 filmPos, const Lanes& lanes, const WalkSettings& ws, Sampler& rng,
                        RayCounter& counter, std::vector<PathVertex>& out);

// L[0] is the light vertex, its pdfFwd its position's density, its choicePdf that of its light (with
// the light-start wavelength density in the own family). A shared subpath carries the camera sample's lanes and
// stops at its first fluorescent event (later vertices could only form paths the shared family
// cannot weight); an own one has one lane.
void traceLightSubpath(const Scene& scene, LightFamily family, const Lanes& shared, const WalkSettings& ws, Sampler& rng,
                       RayCounter& counter, std::vector<PathVertex>& out);

// The unified estimator's one light subpath for both families (docs/bdpt-mis.md §11), started by
// ws.lightFirst: the light with Q(l), its own wavelength with p_l(λ). One walk, two views of it: LO
// the own wavelength's (as traceLightSubpath's own family; its choicePdf Q(l)·p_l(λ_0)), LS the
// camera sample's lanes (as its shared family; choicePdf Q(l)). Where sampling depends on the
// wavelength and both go on, LS forks and goes on alone. Returns how many vertices the two views
// share (each the same point in both; all of them if LS never forked).
int traceMergedLightSubpath(const Scene& scene, const Lanes& shared, const WalkSettings& ws, Sampler& rng,
                            RayCounter& counter, std::vector<PathVertex>& LS, std::vector<PathVertex>& LO);

}  // namespace kasha::bidir
