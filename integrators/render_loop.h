#pragma once
// Runs an integrator over the image: passes of a few samples per pixel over 16×16 tiles in
// parallel (TBB), optionally dealt among processes (render_group.h). Sample s of pixel (x, y)
// draws its random numbers from a Sampler (core/sampler.h) determined by (seed, pixel, s) alone, so
// the image depends neither on the number of threads nor on the number of processes.
//
// Bit-identical results. Each pass is traced into a record and committed to the film in pass
// order (render_pass.h): a pixel's camera samples are added to its sum in sample order, splats in
// tile order after each pass, so a pixel's splat sum depends on how samples are grouped into
// passes: with the same samples per pass (stored in checkpoints) a render resumed at a pass
// boundary, or split among processes, adds exactly the same numbers in exactly the same order as
// an uninterrupted one-process render.
#include <atomic>
#include <functional>
#include <string>

#include <nlohmann/json.hpp>

#include "core/film.h"
#include "core/spectral_film.h"
#include "integrators/integrator.h"
#include "integrators/render_group.h"

namespace kasha {

// Times, sample and ray counts cover this run (not the runs a resumed render continues); spp and
// nonFiniteSamples are the film's totals.
struct RenderStats {
  std::string integrator;
  double seconds = 0.0;
  int spp = 0;
  uint64_t samples = 0, rays = 0, closestRays = 0, shadowRays = 0;
  double samplesPerSecond = 0.0, raysPerSecond = 0.0;
  uint64_t nonFiniteSamples = 0;
  int threads = 0;
  int samplesPerPass = 0;
  bool interrupted = false;  // stopped by RenderOptions::stop before reaching spp or the time budget
  int stopSignal = 0;        // the stop value that ended it (the highest over the processes)
  int ranks = 1;             // processes that rendered (RenderOptions::group); counts and rays are their sums
  std::string choices;       // what the integrator decided (Integrator::choices), empty if nothing
};

// At least ~64k samples per pass, so that small images keep every core busy.
int defaultSamplesPerPass(int width, int height);

struct RenderOptions {
  int spp = 16;                  // stop after this many samples per pixel (counting startSpp)
  double timeBudgetSeconds = 0;  // > 0: stop after the first pass that ends past this time
  uint64_t seed = 1;
  SamplerKind sampler = SamplerKind::Sobol;  // RenderSettings::sampler
  int threads = 0;               // 0: all cores
  // Called after every pass with (samples per pixel so far, seconds so far, estimated total seconds).
  std::function<void(int, double, double)> progress;

  // Resuming (core/checkpoint.h): the film already holds startSpp samples per pixel, and
  // previousSeconds of rendering count towards the time budget.
  int startSpp = 0;
  double previousSeconds = 0.0;
  // Samples per pixel in one pass; 0: defaultSamplesPerPass(). Passes cover samples
  // [k·n, (k+1)·n); a resumed render must use the value of the checkpoint to merge splats in
  // the same order as an uninterrupted render.
  int samplesPerPass = 0;
  // Checked between passes: non-zero stops the render after the current pass (a signal handler
  // sets it; the estimate stays consistent because every pixel has the same sample count).
  const std::atomic<int>* stop = nullptr;
  // Called between passes, once checkpointIntervalSeconds have passed since the last call (0:
  // after every pass), and after the last pass, with the statistics so far. The film is not
  // being written while it runs.
  std::function<void(const RenderStats&)> checkpoint;
  double checkpointIntervalSeconds = 60.0;
  // If set, integrators that can record each strategy's share of their samples
  // (SampleContext::recordStrategies), and this receives the records after each pass, in tile order.
  std::function<void(const StrategySample&)> strategies;
  // If set (same size as the film), also receives every sample's spectral shares; the XYZ film's
  // non-finite samples are left out of it too. In a group, only rank 0's receives them (every
  // rank must still set one, so that its passes record the shares).
  SpectralFilm* spectral = nullptr;
  // The processes rendering this image together; nullptr: this one alone. All of them call
  // render() with the same options; only rank 0's film receives samples, and only rank 0 calls
  // progress, checkpoint and strategies. A stop request on any rank stops all after the same pass;
  // rank 0's clock decides the time budget.
  RenderGroup* group = nullptr;
  // In a group: what else determines the image (RenderJob: its checkpoint settings, with the
  // scene's hash and the integrator's). Before anything else is exchanged, rank 0 checks that every
  // rank renders with the same record, these options' own fields added (requireSameRecord,
  // rank_agreement.h).
  nlohmann::json image = nlohmann::json::object();
};

// Renders into `film` until options.spp, the time budget or a stop request; returns the
// statistics (on rank 0 of a group: summed over the ranks).
RenderStats render(const Scene& scene, const Integrator& integrator, Film& film, const RenderOptions& options);

nlohmann::json toJson(const RenderStats& s);
// One line for the terminal: time, spp, samples/s, rays/s.
std::string summaryLine(const RenderStats& s);
}  // namespace kasha
