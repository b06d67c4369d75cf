#pragma once
// Bidirectional path tracing for bispectral scenes (docs/bdpt-mis.md): every (s, t) strategy,
// densities both ways, every wavelength density in the MIS weights, and the two exact wavelength
// families of docs/transport.md §3 — light subpaths sharing the camera sample's wavelength (shared),
// joined to elastic camera vertices on paths that never fluoresce, and light subpaths drawing their
// own from the light-start strategy, by default the lights' power spectrum (own), joined through a
// connection vertex that evaluates its fluorescent lobe. By default both in one MIS
// (docs/bdpt-mis.md §5), on one light subpath that carries both (§11), with a pilot that may run one
// family alone (§13); render/bdpt/families fixes the choice.
// The sensor and light-start strategies must be densities (single or mix:), which enter the MIS
// weights. Optionally (the own family alone) spectral mollification joins elastic connection
// vertices through a wavelength kernel whose half-width shrinks pass by pass (render/bdpt/mollify,
// docs/bdpt-mis.md §6); each pass then takes one sample per pixel.
#include "scene/wavelength_strategy.h"
#include <memory>
#include <mutex>
#include <optional>

#include "integrators/bidirectional/light_first.h"
#include "integrators/bidirectional/mis.h"
#include "integrators/bidirectional/subpaths.h"
#include "integrators/integrator.h"

namespace kasha {
namespace bidir {
class MisObserver;  // mis_observer.h
}

class Bdpt final : public Integrator {
 public:
  // Throws std::invalid_argument if a wavelength strategy does not apply (docs/wavelength-sampling.md)
  // or render/bdpt is out of range (checkBdptSettings).
  Bdpt(const Scene& scene, const RenderSettings& settings);
  Vec3 samplePixel(const Scene& scene, Vec2 pixel, Sampler& rng, SampleContext& ctx) const override;
  std::string name() const override;
  int lanes() const override { return lanes_; }
  // Its (s, t) strategies can be shown one image each (strategy_images.h, docs/bdpt-mis.md §7).
  Capabilities capabilities() const override { return {lanes_, true, true}; }
  std::unique_ptr<const PassData> beginPass(const Scene& scene, int firstSample, int count, uint64_t seed,
                                            RayCounter& counter) const override;
  int maxSamplesPerPass() const override;
  std::string choices() const override;

  bool mollifies() const { return bandwidth1_ > 0.0f; }
  // The kernel half-width h_i of the pass that takes sample `sample` (iteration sample + 1):
  // h_i = h_1·r_i/r_1 with the radius schedule of progressive photon mapping.
  float bandwidth(int sample) const;

  // The pilot's decision for a render with `seed` (docs/bdpt-mis.md §13): both families, or one of
  // them alone (Both, Shared or Own). Computed once per seed (the render's first pass asks);
  // `counter` is set to the rays it traced when it runs (left alone when the decision was known).
  BdptFamilies pilotChoice(const Scene& scene, uint64_t seed, RayCounter& counter) const;

 private:
  // The families a sample of the pass `pass` runs (the unified estimator's families choice or its
  // pilot's decision): Both, Shared or Own.
  BdptFamilies familiesOf(const PassData* pass) const;
  // One camera sample of pixel `pixel` (its integer corner) with the mode's families, or (unified
  // estimator) with `run`'s: the sample's estimate; splats go to ctx. `observer` (the pilot's) watches
  // it, or else, where ctx asks for them, the per-strategy images.
  Vec3 estimate(const Scene& scene, Vec2 pixel, Sampler& rng, SampleContext& ctx, BdptFamilies run,
                bidir::MisObserver* observer) const;

  WavelengthStrategy sensor_, light_;
  bidir::WalkSettings ws_;
  bidir::WalkSettings wsAlone_;  // the unified estimator's when it runs one family alone
  BdptFamilies familyChoice_ = BdptFamilies::Both;
  bidir::WavelengthMode mode_;
  bidir::Families families_;
  float bandwidth1_ = 0.0f, alpha_ = 0.0f;
  int lanes_ = 1;  // wavelength lanes per camera sample (docs/bdpt-mis.md §10)
  std::vector<Vec3> directXyz_;  // per light: its emission's XYZ seen directly (direct_emission.h)
  // The unified estimator's merged light subpath starts here (both families run; docs/bdpt-mis.md §11).
  std::unique_ptr<bidir::LightFirstStart> lightFirst_;
  // The pilot's outcome, per render seed (BdptFamilies::Auto).
  struct PilotOutcome {
    uint64_t seed = 0;
    BdptFamilies run = BdptFamilies::Both;
    // Per estimator (both, shared alone, own alone; docs/bdpt-mis.md §13): whether it samples every
    // path that carries light, its relative variance per sample (the alone ones from both families'
    // paths), rays per sample and the cost per sample these give.
    struct Candidate {
      bool samplesAll = true;
      double relVar = 0.0, rays = 0.0, cost = 0.0;
    };
    Candidate both, shared, own;
  };
  mutable std::mutex pilotMutex_;
  mutable std::optional<PilotOutcome> pilot_;
};

}  // namespace kasha
