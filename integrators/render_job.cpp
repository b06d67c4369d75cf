#include "integrators/render_job.h"

#include <malloc.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <mutex>

#include "core/checkpoint.h"
#include "core/error.h"
#include "core/json_fields.h"
#include "core/memory_budget.h"
#include "integrators/integrator_factory.h"
#include "integrators/render_pass.h"

namespace kasha {

void keepHeapBetweenPasses() {
  // glibc hands freed heap back to the system as soon as 128 KiB lie free at its top, and maps
  // blocks from 128 KiB on (a threshold it raises as it goes): every pass frees and allocates
  // again its megabytes (photon maps, light vertices, FLANN's trees, per-chunk buffers), which the
  // system then faults in anew. Kept instead (blocks up to 32 MiB from the heap, never trimmed), the
  // viewing booth at 16 spp renders with vcm in 9% less time, with ppm in 4% less, pt and bdpt as
  // before, at the same peak memory within 3 MB (docs/benchmarks.md, "Heap kept between passes").
  static std::once_flag once;
  std::call_once(once, [] {
    mallopt(M_MMAP_THRESHOLD, 32 << 20);
    mallopt(M_TRIM_THRESHOLD, std::numeric_limits<int>::max());
  });
}

namespace {

// The film's buffers: the XYZ sums and the spectral bins (twice while a checkpoint is read into
// them) and the output's float channels (six and one per bin).
void requireFilmMemory(int width, int height, const SpectralBins& bins, bool resuming, uint64_t limit) {
  const uint64_t sums = Film::bytesFor(width, height) + SpectralFilm::bytesFor(width, height, bins.count);
  const uint64_t channels = saturatingMul(uint64_t(width) * uint64_t(height) * sizeof(float), 6 + uint64_t(bins.count));
  requireMemory(saturatingMul(sums, resuming ? 2 : 1) + channels,
                "the film (" + std::to_string(width) + "x" + std::to_string(height) + " pixels" +
                    (bins.enabled() ? ", " + std::to_string(bins.count) + " spectral bins" : "") + ")",
                limit);
}

// A pass's camera samples wait in a record before they reach the film (render_pass.h):
// `samplesPerPass` per pixel, 0 for the default the integrator allows.
void requirePassMemory(const Integrator& integrator, int width, int height, int samplesPerPass, bool spectral,
                       uint64_t limit) {
  const int perPass =
      samplesPerPass > 0 ? samplesPerPass : std::min(defaultSamplesPerPass(width, height), integrator.maxSamplesPerPass());
  requireMemory(PassTracer::sampleBytes(width, height, perPass, spectral),
                "the samples of one pass (" + std::to_string(perPass) + " per pixel)", limit);
}

SpectralBins binsFor(const Scene& scene, int count, double step) {
  if (count < 0 || !(step >= 0.0))
    throw RenderJobError(count < 0 ? "spectral_bins" : "spectral_step", "must be positive (0: no spectral bins)");
  if (count > 0 && step > 0.0) throw RenderJobError("spectral_step", "give spectral bins or their step, not both");
  try {
    if (count > 0) return SpectralBins::fromCount(scene.range, count);
    if (step > 0.0) return SpectralBins::fromStep(scene.range, step);
  } catch (const std::invalid_argument& e) {
    throw RenderJobError(count > 0 ? "spectral_bins" : "spectral_step", e.what());
  }
  return {};
}

}  // namespace

RenderJob::RenderJob(const Scene& scene, RenderJobOptions options) : scene_(scene), options_(std::move(options)) {
  keepHeapBetweenPasses();
  RenderJobOptions& o = options_;
  // An alias's settings are its own: a caller's setting of the same key would be overruled.
  for (const IntegratorAlias& alias : integratorAliases()) {
    if (alias.name != o.integrator) continue;
    for (const std::string& key : o.setKeys)
      for (const std::string& set : alias.settings) {
        const std::string aliasKey = set.substr(0, set.find('='));
        if (key == aliasKey || key.rfind(aliasKey + ".", 0) == 0 || aliasKey.rfind(key + ".", 0) == 0)
          throw RenderJobError(key, "the integrator " + alias.name + " stands for " + alias.integrator + " with " + set +
                                        " (choose " + alias.integrator + " to set it)");
      }
  }
  o.integrator = resolveIntegrator(o.integrator, o.settings);
  for (const std::string& key : o.setKeys)
    if (const std::string why = settingNotRead(o.integrator, key); !why.empty()) throw RenderJobError(key, why);
  const bool strategyImages = o.strategyDepth >= 0;
  // Per-strategy images are of vcm's strategies: camera paths alone (pt) have none to show.
  if (strategyImages && o.settings.vcm.paths == VcmPaths::Auto) o.settings.vcm.paths = VcmPaths::Bidirectional;
  integrator_ = makeIntegrator(o.integrator, scene, o.settings);
  const Capabilities can = integrator_->capabilities();
  // A resumed render keeps checkpointing into the file it resumes from unless another is named.
  if (o.checkpoint.empty()) o.checkpoint = o.resume;
  bins_ = binsFor(scene, o.spectralBins, o.spectralStep);
  if (bins_.enabled() && !can.spectralBins)
    throw RenderJobError(o.spectralBins > 0 ? "spectral_bins" : "spectral_step", "the integrator " + o.integrator + " keeps none");
  if (strategyImages) {
    if (!can.strategyImages)
      throw RenderJobError("strategy_images", "the integrator " + o.integrator +
                                                  " has no (s, t) strategies (the bidirectional engine's integrators have; "
                                                  "docs/integrators.md)");
    if (!o.checkpoint.empty())
      throw RenderJobError("strategy_images", "cannot be combined with --checkpoint or --resume");
  }
}

RenderJob::~RenderJob() = default;

nlohmann::json RenderJob::settingsRecord() const {
  const RenderSettings& r = options_.settings;
  nlohmann::json j = {{"seed", r.seed},
                      {"sampler", toString(r.sampler)},
                      {"sensor_sampling", r.wavelengths.sensor.text},
                      {"fluorescence_sampling", r.wavelengths.fluorescence.text},
                      {"light_sampling", r.wavelengths.light.text},
                      {"nee_sampling", r.wavelengths.nee.text},
                      {"hero_wavelengths", integrator_->lanes()},
                      {"fluorescent_lanes", toString(r.fluorescentLanes)},
                      {"max_depth", r.maxDepth}};
  // The integrators' own settings that change the estimator, wherever the integrator reads them
  // (settingNotRead, integrator_factory.h): a checkpoint must not be resumed under others.
  const auto reads = [&](const char* key) { return settingNotRead(options_.integrator, key).empty(); };
  // Each object with the fields the integrator reads (vc: vcm's photons per pass, not its radius).
  const auto record = [&](const char* object, const nlohmann::json& fields) {
    for (const auto& [key, value] : fields.items())
      if (reads((std::string(object) + "." + key).c_str())) j[object][key] = value;
  };
  const BdptSettings& b = r.bdpt;
  record("bdpt", {{"families", toString(b.families)}, {"mollify", b.mollify}, {"mollify_bandwidth", b.mollifyBandwidth},
                  {"mollify_alpha", b.mollifyAlpha}});
  const auto progressive = [](const ProgressiveSettings& p) {
    return nlohmann::json{{"photons_per_pass", p.photonsPerPass}, {"radius", p.radius}, {"alpha", p.alpha},
                          {"bandwidth", p.bandwidth}, {"volume_radius", p.volumeRadius}};
  };
  nlohmann::json vcm = progressive(r.vcm);
  vcm["paths"] = toString(r.vcm.paths);
  record("vcm", vcm);
  nlohmann::json ppm = progressive(r.ppm);
  ppm.update({{"always_wavelength_kernel", r.ppm.alwaysKernel}, {"direct", toString(r.ppm.direct)},
              {"nee_wavelengths", r.ppm.neeWavelengths}});
  record("ppm", ppm);
  return j;
}

nlohmann::json RenderJob::checkpointSettings() const {
  const RenderSettings& r = options_.settings;
  nlohmann::json settings = settingsRecord();
  settings.update({{"scene_hash", options_.sceneHash},
                   {"integrator", integrator_->name()},
                   {"rr_depth", r.rrDepth},
                   {"hide_emitters", r.hideEmitters},
                   {"resolution", {scene_.camera.width(), scene_.camera.height()}},
                   {"spectral_bins", bins_.enabled() ? nlohmann::json{bins_.min, bins_.step, bins_.count}
                                                     : nlohmann::json(nullptr)}});
  return settings;
}

void RenderJob::run() {
  const RenderJobOptions& o = options_;
  const uint64_t limit = o.settings.memoryLimit;
  const int width = scene_.camera.width(), height = scene_.camera.height();
  if (o.strategyDepth >= 0) {
    requireMemory(bidir::StrategyImages::bytesFor(width, height, o.strategyDepth),
                  "the strategy images (depth " + std::to_string(o.strategyDepth) + ")", limit);
    strategies_ = std::make_unique<bidir::StrategyImages>(width, height, o.strategyDepth, scene_.pixelFilter);
  }
  const nlohmann::json settings = checkpointSettings();
  requireFilmMemory(width, height, bins_, !o.resume.empty(), limit);
  film_ = std::make_unique<Film>(width, height);
  if (bins_.enabled()) spectral_ = std::make_unique<SpectralFilm>(width, height, bins_);
  RenderOptions opt;
  opt.spp = o.settings.spp;
  opt.timeBudgetSeconds = o.settings.timeBudgetSeconds;
  opt.seed = o.settings.seed;
  opt.sampler = o.settings.sampler;
  opt.threads = o.threads;
  opt.group = o.group;
  opt.image = settings;  // ranks that disagree on it are refused before the first pass
  if (!o.resume.empty()) {
    CheckpointData d = readCheckpoint(o.resume);
    requireSameSettings(d.settings, settings, o.resume);
    JsonFields run(d.run, o.resume, "/run");
    opt.samplesPerPass = run.integer("samples_per_pass");
    if (opt.samplesPerPass < 1) run.fail("samples_per_pass", "must be at least 1");
    const nlohmann::json& seconds = run.get("seconds");
    opt.previousSeconds = seconds.is_number() ? seconds.get<double>() : -1.0;
    if (!(opt.previousSeconds >= 0.0 && std::isfinite(opt.previousSeconds)))
      run.fail("seconds", "expected a finite number of seconds, at least 0");
    opt.startSpp = d.spp;
    resumed_ = {{"checkpoint", o.resume}, {"spp", d.spp}, {"seconds", opt.previousSeconds}};
    restoreFilm(std::move(d), *film_, spectral_.get());
  }
  previousSeconds_ = opt.previousSeconds;
  requirePassMemory(*integrator_, width, height, opt.samplesPerPass, bins_.enabled(), limit);
  if (!o.checkpoint.empty()) {
    opt.checkpointIntervalSeconds = o.checkpointIntervalSeconds;
    opt.checkpoint = [&](const RenderStats& s) {
      const nlohmann::json run = {{"scene", scene_.path}, {"samples_per_pass", s.samplesPerPass},
                                  {"seconds", opt.previousSeconds + s.seconds}};
      try {
        writeCheckpoint(o.checkpoint, settings, run, *film_, spectral_.get());
      } catch (const std::exception& e) {  // a full disk must not end an overnight render
        std::fprintf(stderr, "kasha: warning: %s\n", e.what());
      }
    };
  }
  if (strategies_) opt.strategies = [&](const StrategySample& rec) { strategies_->add(rec); };
  opt.stop = o.stop;
  opt.spectral = spectral_.get();
  opt.progress = o.progress;
  stats_ = render(scene_, *integrator_, *film_, opt);
  if (strategies_) strategies_->setSamplesPerPixel(film_->samplesPerPixel());
}

nlohmann::json RenderJob::statistics() const {
  nlohmann::json j = toJson(stats_);
  j["scene"] = scene_.path;
  j.update(settingsRecord());
  j["resolution"] = {film_->width(), film_->height()};
  if (stats_.nonFiniteSamples)
    j["first_non_finite_pixel"] = {film_->firstNonFinitePixel().first, film_->firstNonFinitePixel().second};
  j["total_seconds"] = previousSeconds_ + stats_.seconds;
  if (!resumed_.is_null()) j["resumed"] = resumed_;
  if (!options_.checkpoint.empty()) j["checkpoint"] = options_.checkpoint;
  if (spectral_) j["spectral_bins"] = {{"min_nm", bins_.min}, {"step_nm", bins_.step}, {"count", bins_.count}};
  return j;
}

}  // namespace kasha
