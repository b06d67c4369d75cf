#pragma once
// One render, as every front end runs it: `kasha render`, `kasha compare` (its reference and each
// integrator's render) and Python's kasha.render. A scene, an integrator's name and the settings
// become a film (with spectral bins and per-strategy images if asked) and a statistics record;
// the job checks what the integrator can do (Integrator::capabilities) and every large buffer
// against the memory limit before it is allocated, writes and resumes checkpoints, and keeps to the
// time budget, the stop flag and the MPI group of the render loop (render_loop.h). The front ends
// read their arguments and write their outputs (docs/cli.md, docs/python.md).
#include <atomic>
#include <functional>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/film.h"
#include "core/spectral_film.h"
#include "integrators/bidirectional/strategy_images.h"
#include "integrators/integrator.h"
#include "integrators/render_loop.h"
#include "scene/render_settings.h"

namespace kasha {

// A job option or setting the integrator cannot use. `setting` names it as the render object does
// ("bdpt.families", "ppm.direct") or as RenderJobOptions does ("strategy_images", "spectral_bins",
// "spectral_step"), so that a front end can name its own option in the message.
struct RenderJobError : std::invalid_argument {
  RenderJobError(std::string setting, const std::string& reason)
      : std::invalid_argument(reason), setting(std::move(setting)) {}
  std::string setting;
};

struct RenderJobOptions {
  std::string integrator = "pt";
  // The scene's render settings with the front end's: stop conditions (spp, time), seed, sampler,
  // strategies, lanes, the integrators' own settings and the memory limit.
  RenderSettings settings;
  // Keys of the render object the caller set (`--set`, Python's keywords): one the integrator does
  // not read is refused (settingNotRead in integrator_factory.h), not silently ignored.
  std::vector<std::string> setKeys;
  int threads = 0;  // 0: all cores
  // Spectral bins: N equal bins of the scene's range, or bins `spectralStep` nm wide; 0: none.
  int spectralBins = 0;
  double spectralStep = 0.0;
  // >= 0: keep one image per (s, t) strategy, paths longer than this in one (strategy_images.h).
  int strategyDepth = -1;
  // Checkpoints (core/checkpoint.h, docs/reliability.md): written to `checkpoint` every
  // checkpointIntervalSeconds and at the end; `resume` continues the render one holds, which must
  // have been made with the same settings (checkpointSettings()).
  std::string checkpoint, resume;
  double checkpointIntervalSeconds = 60.0;
  std::string sceneHash;  // identifies the scene (and its overrides) in checkpoints
  // As RenderOptions: called after every pass; non-zero stops after the current pass; the processes
  // rendering together (nullptr: this one alone).
  std::function<void(int, double, double)> progress;
  const std::atomic<int>* stop = nullptr;
  RenderGroup* group = nullptr;
};

class RenderJob {
 public:
  // Builds the integrator and checks the options against it. Throws what makeIntegrator throws
  // (integrator_factory.h) and RenderJobError. An alias (integratorAliases) becomes the integrator
  // it stands for, with its settings. With strategy images, vcm.paths "auto" becomes
  // "bidirectional": the images are of vcm's strategies, and camera paths alone have none.
  RenderJob(const Scene& scene, RenderJobOptions options);
  ~RenderJob();

  // Checks the film, the strategy images and a pass's samples against the memory limit
  // (MemoryLimitError), reads the checkpoint to resume (InputError), then renders.
  void run();

  const Integrator& integrator() const { return *integrator_; }
  const RenderSettings& settings() const { return options_.settings; }
  const SpectralBins& bins() const { return bins_; }
  // The checkpoint written: RenderJobOptions::checkpoint, else the file resumed; empty for none.
  const std::string& checkpoint() const { return options_.checkpoint; }
  // After run(): the image, its spectral bins and strategy images (nullptr if not asked for), the
  // statistics of this run.
  const Film& film() const { return *film_; }
  const SpectralFilm* spectral() const { return spectral_.get(); }
  bidir::StrategyImages* strategies() { return strategies_.get(); }
  const RenderStats& stats() const { return stats_; }
  // The statistics record (`kasha render`'s .stats.json without the front end's outputs and
  // signal): the render statistics, the settings, resolution, seconds including the runs a
  // resumed render continues, and what was resumed and checkpointed.
  nlohmann::json statistics() const;
  // What a checkpoint must agree on to be resumed; the sample count and time budget may differ
  // (a finished render can be continued to more samples).
  nlohmann::json checkpointSettings() const;

 private:
  // The settings both records name: seed, sampler, the four wavelength strategies, the
  // integrator's lanes (hero_wavelengths), fluorescent_lanes, maximum depth, and of the integrator's
  // own settings (render.bdpt, render.vcm, render.ppm) those it reads.
  nlohmann::json settingsRecord() const;

  const Scene& scene_;
  RenderJobOptions options_;
  std::unique_ptr<Integrator> integrator_;
  SpectralBins bins_;
  std::unique_ptr<Film> film_;
  std::unique_ptr<SpectralFilm> spectral_;
  std::unique_ptr<bidir::StrategyImages> strategies_;
  RenderStats stats_;
  double previousSeconds_ = 0.0;
  nlohmann::json resumed_;
};

// The heap policy of a render (render_job.cpp): set once, by the first RenderJob, in every program
// that renders (the kasha binary, the Python module).
void keepHeapBetweenPasses();

}  // namespace kasha
