#pragma once
// Vertex connection and merging for bispectral scenes (Georgiev et al. 2012; Hachisuka et al. 2012;
// docs/bdpt-mis.md §12): the unified BDPT's connections (both wavelength families, §5–§11) and
// vertex merging at every connectible camera vertex against the light vertices of the pass, in one
// set of recursive power-heuristic weights. Each pass traces N light subpaths (render/vcm/
// photons_per_pass, by default one per pixel) at one set of wavelength lanes shared by every camera
// sample of the pass, so that a merge through an elastic vertex meets light at exactly the camera's
// wavelengths; an own-family light vertex merges through a fluorescent camera vertex, whose lobe
// takes it from its own wavelength to the camera's, or an elastic one through a wavelength kernel
// (with the own family's mollified joins, docs/bdpt-mis.md §6). The radius and the kernel shrink pass
// by pass as in `ppm` (render/vcm/radius, bandwidth, alpha). `vc` has the connections alone (no
// kernel), `bpm` the merges alone (with the camera subpath reaching the light), as SmallVCM's
// algorithm list. `vcm` without light subpaths is path tracing with next-event estimation: a pilot
// chooses per render between it, every strategy, every strategy with the wide final gather, and the
// connections alone (docs/bdpt-mis.md §12, §14, render/vcm/paths). In scenes with media, collisions merge with the
// light vertices in media within a sphere (docs/media.md §6).
#include <memory>
#include <mutex>
#include <optional>

#include "integrators/bidirectional/light_first.h"
#include "integrators/bidirectional/mis.h"
#include "integrators/bidirectional/subpaths.h"
#include "integrators/integrator.h"
#include "scene/wavelength_strategy.h"

namespace kasha {

struct VcmPass;
namespace bidir {
class MisObserver;
}

class Vcm final : public Integrator {
 public:
  enum class Parts : uint8_t { ConnectionsAndMerges, Connections, Merges };

  // Throws std::invalid_argument for settings out of range (more than bidir::kLightVertexLanes lanes,
  // radius, alpha), WavelengthStrategyError for a strategy that is not a density, MemoryLimitError
  // where a pass cannot fit the memory limit.
  Vcm(const Scene& scene, const RenderSettings& settings, Parts parts);
  ~Vcm() override;
  std::unique_ptr<const PassData> beginPass(const Scene& scene, int firstSample, int count, uint64_t seed,
                                            RayCounter& counter) const override;
  int maxSamplesPerPass() const override { return 1; }
  Vec3 samplePixel(const Scene& scene, Vec2 pixel, Sampler& rng, SampleContext& ctx) const override;
  std::string name() const override;
  int lanes() const override { return lanes_; }
  // Its connections and merges are (s, t) strategies of the BDPT kind (docs/bdpt-mis.md §7, §12).
  Capabilities capabilities() const override { return {lanes_, true, true}; }
  std::string choices() const override;

  // The pilot's decision for a render with `seed` (docs/bdpt-mis.md §14): Bidirectional, Gather,
  // Connections or Camera.
  // Computed once per seed (the render's first pass asks); `counter` is set to the rays it traced
  // when it runs (left alone when the decision was known).
  VcmPaths pilotChoice(const Scene& scene, uint64_t seed, RayCounter& counter) const;

  // The merge radius of the pass that takes sample `sample` (iteration sample + 1).
  float radius(int sample) const;
  // The radius of merges at collisions in media (docs/media.md §6), shrinking by Knaus and Zwicker's
  // schedule for three dimensions; 0 in a scene without media.
  float volumeRadius(int sample) const;
  size_t lightPathsPerPass() const { return paths_; }

 private:
  // The pass that takes sample `firstSample` for `run` (Bidirectional, Gather or Connections): its
  // lanes, and but for the connections alone its radius and light vertices, with the wide gather or
  // not; with `paths` > 0, at most that many light subpaths (the radius widened to keep the pass's η).
  std::unique_ptr<VcmPass> bidirectionalPass(const Scene& scene, int firstSample, uint64_t seed, VcmPaths run,
                                             RayCounter& counter, size_t paths = 0) const;
  // One camera sample of every strategy against `pass`; `observer` (the pilot's) watches it, or else,
  // where ctx asks for them, the per-strategy images.
  Vec3 estimate(const Scene& scene, Vec2 pixel, Sampler& rng, SampleContext& ctx, const VcmPass& pass,
                bidir::MisObserver* observer) const;

  WavelengthStrategy sensor_, light_;
  Parts parts_;
  bidir::WalkSettings ws_;
  bidir::Families families_;
  std::unique_ptr<bidir::LightFirstStart> lightFirst_;  // both families: the merged light subpath's start
  int lanes_;
  size_t paths_;
  float radius1_, alpha_;
  float volumeRadius1_ = 0.0f;  // render/vcm/volume_radius, or from a pilot; 0 without media
  bool beams_ = false;  // light vertices in media also merge with the camera's query beams (render/vcm/beams)
  bool photonBeams_ = false;  // and the light subpaths' flights through media (render/vcm/photon_beams)
  float bandwidth1_ = 0.0f;  // the first pass's wavelength kernel half-width (0: no kernel)
  uint64_t memoryLimit_;
  SamplerKind sampler_;
  std::vector<Vec3> directXyz_;  // per light: its emission's XYZ seen directly (direct_emission.h)
  // vcm only: camera paths alone (pt's estimator with these settings), and which subpaths run.
  std::unique_ptr<Integrator> cameraAlone_;
  VcmPaths pathsChoice_ = VcmPaths::Bidirectional;
  // The pilot's outcome, per render seed (VcmPaths::Auto).
  struct PilotOutcome {
    uint64_t seed = 0;
    VcmPaths run = VcmPaths::Bidirectional;
    bool cameraSamplesAll = true;  // camera paths alone sample every path that carries light
    // Relative variance per sample (camera paths alone's from vcm's paths, times what their own
    // samples gain from the render's stratified random numbers) and rays per sample.
    double relVar = 0.0, rays = 0.0, cameraRelVar = 0.0, cameraRays = 0.0, stratification = 1.0;
    // With the merges' cost (kRaysPerMergeWeight); the wide gather's relative variance and cost,
    // where it differs (a scene that fluoresces: own light vertices).
    double cost = 0.0, gatherRelVar = 0.0, gatherCost = 0.0;
    // The connections alone (vc's estimator): whether they sample every path that carries light,
    // their relative variance per sample (from vcm's paths) and rays per sample.
    bool connectionsSamplesAll = true;
    double connectionsRelVar = 0.0, connectionsRays = 0.0;
    bool gatherDiffers = true;
  };
  mutable std::mutex pilotMutex_;
  mutable std::optional<PilotOutcome> pilot_;
};

}  // namespace kasha
