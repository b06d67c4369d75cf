// kasha: the command-line program. `kasha render` renders a scene; `kasha matrix` exports the
// reradiation matrix of a fluorescent material (Jung18 eq. 5); `kasha compare` and `kasha metrics`
// measure renders against a reference.
//
// Exit codes: 0 done; 1 bad input (scene, spectrum, mesh, checkpoint), a memory limit or a failed
// write, one line "kasha: error: ..." and nothing written; 2 a command-line mistake (CLI11's parse
// errors and UsageError: an option's value, a combination the integrator refuses, an output path
// checked by checkOutputs before the first sample); 128 + signal (130 SIGINT,
// 143 SIGTERM) when a render was asked to stop: it finishes the current pass and writes the image,
// the statistics and the checkpoint (if any) before exiting.
//
// `mpirun -np N kasha render ...` (detected, or --mpi) renders one image with N processes
// (cli/mpi_group.h); rank 0 writes the outputs, an error on any rank ends all with its exit code.
#include <CLI/CLI.hpp>
#include <malloc.h>
#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <limits>
#include <map>
#include <sstream>

#include "cli/compare_command.h"
#include "cli/metrics_command.h"
#include "cli/mpi_group.h"
#include "cli/extract_command.h"
#include "cli/progress.h"
#include "core/checkpoint.h"
#include "core/error.h"
#include "core/image_output.h"
#include "core/memory_budget.h"
#include "core/output_file.h"
#include "core/spectral_film.h"
#include "scene/scene_loader.h"
#include "integrators/bdpt/bdpt_integrator.h"
#include "integrators/bdpt/strategy_images.h"
#include "integrators/vcm/vcm_integrator.h"
#include "scene/wavelength_strategy.h"
#include "integrators/integrator_factory.h"
#include "integrators/photon_mapping/direct_light_wavelengths.h"
#include "integrators/render_loop.h"
#include "integrators/render_setup.h"
#include "materials/jung_bbrrdf.h"

namespace kasha {
namespace {

// Set by SIGINT/SIGTERM: the number of the signal. The render loop checks it between passes; the
// handler does nothing else that is not async-signal-safe.
std::atomic<int> gStopSignal{0};
static_assert(std::atomic<int>::is_always_lock_free, "the signal handler needs a lock-free flag");

bool gStderrIsTty = false;  // set before the handler is installed: isatty is not async-signal-safe

extern "C" void onStopSignal(int sig) {
  if (gStopSignal.load() != 0) _exit(128 + sig);  // a second signal: stop at once, writing nothing
  gStopSignal.store(sig);
  static const char msg[] =
      "\nkasha: stopping after the current pass to write the image (signal again to quit at once)\n";
  // The leading newline ends a progress bar's line; without one it would be an empty line.
  const size_t skip = gStderrIsTty ? 0 : 1;
  const ssize_t ignored = write(STDERR_FILENO, msg + skip, sizeof msg - 1 - skip);
  (void)ignored;
}

void installStopHandlers() {
  gStderrIsTty = isatty(STDERR_FILENO) != 0;
  struct sigaction sa {};
  sa.sa_handler = onStopSignal;
  sigemptyset(&sa.sa_mask);
  sa.sa_flags = SA_RESTART;
  sigaction(SIGINT, &sa, nullptr);
  sigaction(SIGTERM, &sa, nullptr);
}

struct RenderArgs {
  std::string scene, output, png;
  bool noPng = false, quiet = false;
  int spp = 0, threads = 0, maxDepth = -1;
  double time = -1.0;
  int64_t seed = -1;
  std::string integrator = "pt";
  bool integratorGiven = false;  // --integrator on the command line
  std::string sensor, fluorescence, light, nee;
  int hero = 0;
  std::string fluorescentLanes;  // empty: the scene's
  std::string bdptFamilies;      // empty: the scene's
  std::string vcmPaths;          // empty: the scene's
  std::string sampler;
  float exposure = 0.0f;
  std::string checkpoint, resume;
  double checkpointInterval = 60.0;
  std::string memoryLimit = "8G";
  float mollifyBandwidth = -1.0f, mollifyAlpha = -1.0f;  // negative: the scene's
  std::string ppmDirect, ppmNeeWavelengths;              // empty: the scene's render/ppm
  std::string strategyImages;  // directory for one image per BDPT strategy
  bool strategyUnweighted = false;
  int strategyDepth = 4;
  int spectralBins = 0;        // 0: none
  float spectralStep = 0.0f;   // nm; 0: none
  bool mpi = false;  // initialise MPI even if no MPI launcher is detected
};

struct MatrixArgs {
  std::string scene, material, output;
  float step = 5.0f;
  std::string memoryLimit = "8G";
};

std::string withExtension(const std::string& path, const std::string& ext) {
  return std::filesystem::path(path).replace_extension(ext).string();
}

std::string hex(uint64_t v) {
  char buf[17];
  std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(v));
  return buf;
}

const char* signalName(int sig) { return sig == SIGINT ? "SIGINT" : sig == SIGTERM ? "SIGTERM" : "signal"; }

// group: the MPI ranks rendering together, or nullptr; only rank 0 writes files and prints.
int runRender(const RenderArgs& a, RenderGroup* group) {
  const uint64_t memoryLimit = parseByteSize(a.memoryLimit);  // validated by the option's check
  SceneLoadOptions load;
  load.memoryLimit = memoryLimit;
  // Read once: the text is both loaded and hashed for checkpoints.
  const std::string sceneText = readSceneFile(a.scene);
  std::unique_ptr<Scene> scene = loadSceneFromString(sceneText, a.scene, load);
  RenderSettings& r = scene->render;
  if (a.spp > 0) r.spp = a.spp;
  if (a.time >= 0.0) r.timeBudgetSeconds = a.time;
  if (a.time > 0.0 && a.spp <= 0) r.spp = 1 << 30;  // a time budget alone decides
  if (a.seed >= 0) r.seed = uint64_t(a.seed);
  if (a.maxDepth >= 0) r.maxDepth = a.maxDepth;
  // Validated by the options' checks.
  if (!a.sensor.empty()) r.wavelengths.sensor = parseWavelengthSpec(a.sensor);
  if (!a.fluorescence.empty()) r.wavelengths.fluorescence = parseWavelengthSpec(a.fluorescence);
  if (!a.light.empty()) r.wavelengths.light = parseWavelengthSpec(a.light);
  if (!a.nee.empty()) r.wavelengths.nee = parseWavelengthSpec(a.nee);
  if (a.hero > 0) r.heroWavelengths = a.hero;
  if (!a.fluorescentLanes.empty()) r.fluorescentLanes = *parseFluorescentLanes(a.fluorescentLanes);  // validated
  if (!a.bdptFamilies.empty()) {
    if (a.integrator != "bdpt") throw UsageError("--bdpt-families", "", "only for --integrator bdpt");
    r.bdptFamilies = *parseBdptFamilies(a.bdptFamilies);  // validated by the option's check
  }
  if (!a.vcmPaths.empty()) {
    if (a.integrator != "vcm") throw UsageError("--vcm-paths", "", "only for --integrator vcm");
    r.vcmPaths = *parseVcmPaths(a.vcmPaths);  // validated by the option's check
  }
  // Per-strategy images are of vcm's strategies: camera paths alone (pt) have none to show.
  if (!a.strategyImages.empty() && r.vcmPaths == VcmPaths::Auto) r.vcmPaths = VcmPaths::Bidirectional;
  if (!a.sampler.empty()) r.sampler = *parseSamplerKind(a.sampler);  // validated by the option's check
  r.memoryLimit = memoryLimit;
  if ((a.mollifyBandwidth >= 0.0f || a.mollifyAlpha >= 0.0f) && a.integrator != "bdpt-mollified")
    throw UsageError(a.mollifyBandwidth >= 0.0f ? "--mollify-bandwidth" : "--mollify-alpha", "",
                     "only for --integrator bdpt-mollified");
  if (a.mollifyBandwidth >= 0.0f) r.mollify.bandwidth = a.mollifyBandwidth;
  if (a.mollifyAlpha >= 0.0f) r.mollify.alpha = a.mollifyAlpha;
  if ((!a.ppmDirect.empty() || !a.ppmNeeWavelengths.empty()) && a.integrator != "ppm")
    throw UsageError(a.ppmDirect.empty() ? "--ppm-nee-wavelengths" : "--ppm-direct", "", "only for --integrator ppm");
  if (!a.ppmDirect.empty())  // validated by the option's check
    r.ppm.direct = a.ppmDirect == "nee" ? PpmDirectLight::Nee : a.ppmDirect == "photons" ? PpmDirectLight::Photons : PpmDirectLight::NeeElastic;
  if (!a.ppmNeeWavelengths.empty()) r.ppm.neeWavelengths = a.ppmNeeWavelengths;
  std::unique_ptr<Integrator> integrator;
  try {
    integrator = makeIntegrator(a.integrator, *scene, r);
  } catch (const WavelengthStrategyError& e) {
    // A command-line mistake when the command line chose the strategy or the integrator; else
    // the scene's /render settings do not fit the default integrator.
    std::string option = settingName(e.site());
    std::replace(option.begin(), option.end(), '_', '-');
    const std::map<WavelengthSite, const std::string*> given = {{WavelengthSite::Sensor, &a.sensor},
        {WavelengthSite::Fluorescence, &a.fluorescence}, {WavelengthSite::LightStart, &a.light}, {WavelengthSite::Nee, &a.nee}};
    const auto it = given.find(e.site());
    if (it != given.end() && !it->second->empty()) throw UsageError("--" + option, "", e.what());
    if (a.integratorGiven) throw UsageError("--integrator " + a.integrator, "", std::string(e.what()) + " (/render/" +
                                                                                settingName(e.site()) + " in " + a.scene + ")");
    throw InputError(a.scene, "/render/" + std::string(settingName(e.site())), e.what());
  } catch (const PpmNeeWavelengthsError& e) {
    if (!a.ppmNeeWavelengths.empty()) throw UsageError("--ppm-nee-wavelengths", "", e.what());
    throw InputError(a.scene, "/render/ppm/nee_wavelengths", e.what());
  } catch (const FluorescentLanesError& e) {
    // Only --integrator can name one that refuses it (pt, the default, takes it).
    if (!a.fluorescentLanes.empty()) throw UsageError("--fluorescent-lanes", a.fluorescentLanes, e.what());
    throw UsageError("--integrator " + a.integrator, "",
                     std::string(e.what()) + " (/render/fluorescent_lanes in " + a.scene + ")");
  } catch (const std::invalid_argument& e) {
    throw UsageError(a.hero > 1 ? "--hero" : "--integrator " + a.integrator, "", e.what());
  }

  const std::string exr = a.output.empty() ? std::filesystem::path(a.scene).stem().string() + ".exr" : a.output;
  const std::string png = a.noPng ? "" : (a.png.empty() ? withExtension(exr, ".png") : a.png);
  const std::string stats = withExtension(exr, ".stats.json");
  // --resume keeps checkpointing into the file it resumes from unless --checkpoint names another.
  const std::string checkpoint = a.checkpoint.empty() ? a.resume : a.checkpoint;
  // Every output checked before the first sample: the scene and the files it named have been read
  // by now; a checkpoint may replace the one it resumes (and only that one).
  std::vector<OutputTarget> outputs = {{exr, "-o", ".exr", ""}, {stats, "-o (its statistics)", ".json", ""}};
  if (!png.empty()) outputs.push_back({png, a.png.empty() ? "-o (its PNG)" : "--png", ".png", ""});
  if (!checkpoint.empty()) outputs.push_back({checkpoint, a.checkpoint.empty() ? "--resume" : "--checkpoint", "", a.resume});
  checkOutputs(outputs, {a.resume});
  const int width = scene->camera.width(), height = scene->camera.height();
  SpectralBins bins;
  try {
    if (a.spectralBins > 0) bins = SpectralBins::fromCount(scene->range, a.spectralBins);
    if (a.spectralStep > 0.0f) bins = SpectralBins::fromStep(scene->range, a.spectralStep);
  } catch (const std::invalid_argument& e) {
    throw UsageError(a.spectralBins > 0 ? "--spectral-bins" : "--spectral-step", "", e.what());
  }
  std::unique_ptr<bdpt::StrategyImages> strategies;
  if (!a.strategyImages.empty()) {
    if (!dynamic_cast<const Bdpt*>(integrator.get()) && !dynamic_cast<const Vcm*>(integrator.get()))
      throw UsageError("--strategy-images", "",
                       "only the BDPT integrators have (s, t) strategies (bdpt, bdpt-shared, bdpt-independent, "
                       "bdpt-mollified, vcm, vc, bpm), not '" + a.integrator + "'");
    if (!checkpoint.empty()) throw UsageError("--strategy-images", "", "cannot be combined with --checkpoint or --resume");
    std::error_code ec;
    std::filesystem::create_directories(a.strategyImages, ec);
    if (ec) throw InputError(a.strategyImages, "", "cannot create the strategy image directory: " + ec.message());
    checkOutputs({{(std::filesystem::path(a.strategyImages) / "s0_t2.exr").string(), "--strategy-images", ".exr", ""}});
    requireMemory(bdpt::StrategyImages::bytesFor(width, height, a.strategyDepth),
                  "the strategy images (--strategy-depth " + std::to_string(a.strategyDepth) + ")", memoryLimit);
    strategies = std::make_unique<bdpt::StrategyImages>(width, height, a.strategyDepth);
  }

  // What a checkpoint must agree on to be resumed; the sample count and time budget may differ
  // (a finished render can be continued to more samples).
  nlohmann::json settings = {{"scene_hash", hex(hashBytes(sceneText.data(), sceneText.size()))},
                                   {"integrator", integrator->name()},
                                   {"seed", r.seed},
                                   {"sampler", toString(r.sampler)},
                                   {"max_depth", r.maxDepth},
                                   {"rr_depth", r.rrDepth},
                                   {"sensor_sampling", r.wavelengths.sensor.text},
                                   {"fluorescence_sampling", r.wavelengths.fluorescence.text},
                                   {"light_sampling", r.wavelengths.light.text},
                                   {"nee_sampling", r.wavelengths.nee.text},
                                   {"hero_wavelengths", integrator->lanes()},
                                   {"fluorescent_lanes", toString(r.fluorescentLanes)},
                                   {"bdpt_families", toString(r.bdptFamilies)},
                                   {"vcm_paths", toString(r.vcmPaths)},
                                   {"resolution", {width, height}},
                                   {"spectral_bins", bins.enabled() ? nlohmann::json{bins.min, bins.step, bins.count}
                                                                    : nlohmann::json(nullptr)}};
  if (a.integrator == "bdpt-mollified") settings["mollify"] = {{"bandwidth", r.mollify.bandwidth}, {"alpha", r.mollify.alpha}};

  requireFilmMemory(width, height, bins, !a.resume.empty(), memoryLimit);
  Film film(width, height);
  std::unique_ptr<SpectralFilm> spectral;
  if (bins.enabled()) spectral = std::make_unique<SpectralFilm>(width, height, bins);
  RenderOptions opt = renderOptions(r, a.threads);
  opt.group = group;
  const bool root = !group || group->rank() == 0;
  nlohmann::json resumed;
  if (!a.resume.empty()) {
    CheckpointData d = readCheckpoint(a.resume);
    requireSameSettings(d.settings, settings, a.resume);
    try {
      opt.samplesPerPass = d.run.at("samples_per_pass").get<int>();
      opt.previousSeconds = d.run.at("seconds").get<double>();
    } catch (const nlohmann::json::exception& e) {
      throw InputError(a.resume, "", std::string("checkpoint header is corrupted: ") + e.what());
    }
    if (opt.samplesPerPass < 1 || !(opt.previousSeconds >= 0.0)) throw InputError(a.resume, "", "checkpoint header is corrupted");
    opt.startSpp = d.spp;
    resumed = {{"checkpoint", a.resume}, {"spp", d.spp}, {"seconds", opt.previousSeconds}};
    restoreFilm(std::move(d), film, spectral.get());
  }
  // A pass's camera samples wait in a record before they reach the film (integrators/render_pass.h).
  requirePassMemory(*integrator, width, height, opt.samplesPerPass, bins.enabled(), memoryLimit);
  if (!checkpoint.empty()) {
    opt.checkpointIntervalSeconds = a.checkpointInterval;
    opt.checkpoint = [&](const RenderStats& s) {
      const nlohmann::json run = {{"scene", a.scene}, {"samples_per_pass", s.samplesPerPass},
                                  {"seconds", opt.previousSeconds + s.seconds}};
      try {
        writeCheckpoint(checkpoint, settings, run, film, spectral.get());
      } catch (const std::exception& e) {  // a full disk must not end an overnight render
        std::fprintf(stderr, "kasha: warning: %s\n", e.what());
      }
    };
  }
  if (strategies) opt.strategies = [&](const StrategySample& rec) { strategies->add(rec); };
  opt.stop = &gStopSignal;
  opt.spectral = spectral.get();
  ProgressBar bar(std::filesystem::path(a.scene).filename().string());
  if (!a.quiet && root) opt.progress = [&](int spp, double t, double total) { bar.update(spp, t, total); };
  installStopHandlers();
  const RenderStats st = render(*scene, *integrator, film, opt);
  bar.finish();
  // A stop request on another rank ends this one too.
  const int sig = st.stopSignal != 0 ? st.stopSignal : gStopSignal.load();
  if (!root) return sig != 0 ? 128 + sig : 0;

  writeExr(film, exr, spectral.get());
  if (!png.empty()) writePng(film, png, a.exposure);
  nlohmann::json j = toJson(st);
  j["scene"] = a.scene;
  j.update(settingsRecord(r, *integrator));
  j["resolution"] = {film.width(), film.height()};
  j["first_non_finite_pixel"] = {film.firstNonFinitePixel().first, film.firstNonFinitePixel().second};
  if (!st.nonFiniteSamples) j.erase("first_non_finite_pixel");
  j["total_seconds"] = opt.previousSeconds + st.seconds;
  if (!resumed.is_null()) j["resumed"] = resumed;
  if (!checkpoint.empty()) j["checkpoint"] = checkpoint;
  if (sig != 0) j["signal"] = signalName(sig);
  j["outputs"] = {{"exr", exr}, {"png", png}};
  if (strategies) {
    strategies->setSamplesPerPixel(film.samplesPerPixel());
    j["outputs"]["strategy_images"] = strategies->write(a.strategyImages, a.strategyUnweighted, !png.empty(), a.exposure);
  }
  if (a.integrator == "bdpt-mollified") j["mollify"] = {{"bandwidth", r.mollify.bandwidth}, {"alpha", r.mollify.alpha}};
  if (spectral) j["spectral_bins"] = {{"min_nm", bins.min}, {"step_nm", bins.step}, {"count", bins.count}};
  writeTextFile(stats, j.dump(2) + "\n");
  std::printf("%s\nwrote %s%s%s, %s\n", summaryLine(st).c_str(), exr.c_str(), png.empty() ? "" : ", ", png.c_str(),
              stats.c_str());
  std::fflush(stdout);
  return sig != 0 ? 128 + sig : 0;
}

int runMatrix(const MatrixArgs& a) {
  const uint64_t memoryLimit = parseByteSize(a.memoryLimit);
  SceneLoadOptions load;
  load.memoryLimit = memoryLimit;
  std::unique_ptr<Scene> scene = loadScene(a.scene, load);
  size_t idx = 0;
  while (idx < scene->materialNames.size() && scene->materialNames[idx] != a.material) ++idx;
  if (idx == scene->materialNames.size())
    throw UsageError("--material", a.material, "no material of that name in " + a.scene);
  const auto* jung = dynamic_cast<const JungBbrrdf*>(scene->materials[idx].get());
  if (!jung) throw UsageError("--material", a.material, "not a jung_fluorescent material in " + a.scene);
  if (!a.output.empty()) checkOutputs({{a.output, "-o", "", ""}});
  // Grid points min + i·step up to max (1e-3 nm tolerance); counted in double, so a tiny step is
  // a clear memory error rather than an endless float loop.
  const double span = double(scene->range.max) + 1e-3 - double(scene->range.min);
  const double count = std::floor(span / double(a.step)) + 1.0;
  const uint64_t n = count < 1e9 ? uint64_t(count) : uint64_t(1e9);
  // The matrix in floats plus its CSV text (about 12 characters an entry).
  requireMemory(saturatingMul(saturatingMul(n, n), sizeof(float) + 12),
                "a " + std::to_string(n) + "x" + std::to_string(n) + " matrix (--step " + std::to_string(a.step) + ")",
                memoryLimit);
  std::vector<float> grid;
  for (uint64_t i = 0; i < n; ++i) grid.push_back(float(double(scene->range.min) + double(i) * double(a.step)));
  const ReradiationMatrix m = jung->reradiationMatrix(grid);
  std::ostringstream out;
  out << "# Reradiation matrix (Jung18 eq. 5) of material '" << a.material << "' in " << a.scene << "\n";
  out << "# Rows: input wavelength; columns out_<nm>: output wavelength; each entry is the energy fraction per band.\n";
  out << "wavelength_in_nm";
  for (float l : grid) out << ",out_" << l;
  out << "\n";
  for (size_t i = 0; i < grid.size(); ++i) {
    out << grid[i];
    for (float v : m.m[i]) out << "," << v;
    out << "\n";
  }
  if (a.output.empty()) {
    std::cout << out.str();
  } else {
    writeTextFile(a.output, out.str());
    std::printf("wrote %s (%zu x %zu)\n", a.output.c_str(), grid.size(), grid.size());
  }
  return 0;
}

}  // namespace
}  // namespace kasha

namespace {

// Number checks with short messages (CLI11's own print the range up to DBL_MAX, and let NaN and
// infinity through).
enum class Sign { Any, NonNegative, Positive };
CLI::Validator numberCheck(Sign sign, bool integer, double max = HUGE_VAL) {
  return CLI::Validator(
      [=](std::string& v) {
        char* end = nullptr;
        const double d = std::strtod(v.c_str(), &end);
        if (end == v.c_str() || *end != '\0' || !std::isfinite(d))
          return "expected a finite " + std::string(integer ? "integer" : "number") + ", got '" + v + "'";
        if (integer && d != std::floor(d)) return "expected an integer, got '" + v + "'";
        if (sign == Sign::NonNegative && d < 0.0) return "must not be negative, got '" + v + "'";
        if (sign == Sign::Positive && !(d > 0.0)) return "must be positive, got '" + v + "'";
        if (d > max) {
          char limit[32];
          std::snprintf(limit, sizeof limit, "%.10g", max);
          return "must be at most " + std::string(limit) + ", got '" + v + "'";
        }
        return std::string();
      },
      integer ? (sign == Sign::Positive ? "INT>0" : "INT>=0") : (sign == Sign::Positive ? "NUMBER>0" : sign == Sign::NonNegative ? "NUMBER>=0" : "NUMBER"));
}
// The largest seed a scene file's /render/seed (an int) can hold; the options allow the same.
constexpr double kMaxSeed = 2147483647.0;
const CLI::Validator kIntegratorName(
    [](std::string& v) {
      const std::vector<std::string> names = kasha::integratorNames();
      if (std::find(names.begin(), names.end(), v) != names.end()) return std::string();
      std::string list;
      for (const std::string& n : names) list += (list.empty() ? "" : ", ") + n;
      return "unknown integrator '" + v + "' (" + list + ")";
    },
    "INTEGRATOR");
const CLI::Validator kByteSize(
    [](std::string& v) {
      try {
        kasha::parseByteSize(v);
        return std::string();
      } catch (const std::invalid_argument& e) {
        return std::string(e.what());
      }
    },
    "BYTES");

}  // namespace

int main(int argc, char** argv) {
  using namespace kasha;
  // glibc hands freed heap back to the system as soon as 128 KiB lie free at its top, and maps
  // blocks from 128 KiB on (a threshold it raises as it goes): every pass frees and allocates
  // again its megabytes (photon maps, light vertices, FLANN's trees, per-chunk buffers), which the
  // system then faults in anew. Kept instead (blocks up to 32 MiB from the heap, never trimmed), the
  // viewing booth at 16 spp renders with vcm in 9% less time, with ppm in 4% less, pt and bdpt as
  // before, at the same peak memory within 3 MB (README, "Heap kept between passes").
  mallopt(M_MMAP_THRESHOLD, 32 << 20);
  mallopt(M_TRIM_THRESHOLD, std::numeric_limits<int>::max());
  CLI::App app{"kasha: a bispectral renderer for fluorescence research"};
  app.set_version_flag("--version", "kasha 0.1.0");
  app.require_subcommand(1);

  RenderArgs ra;
  CLI::App* render = app.add_subcommand("render", "Render a scene to OpenEXR, PNG and a statistics JSON");
  render->add_option("scene", ra.scene, "Scene file (JSON)")->required();
  render->add_option("-o,--output", ra.output, "OpenEXR output (default: <scene name>.exr)");
  render->add_option("--png", ra.png, "PNG output (default: beside the EXR)");
  render->add_flag("--no-png", ra.noPng, "Do not write a PNG");
  render->add_option("--spp", ra.spp, "Samples per pixel (overrides the scene)")->check(numberCheck(Sign::Positive, true));
  render->add_option("--time", ra.time, "Time budget in seconds (whole passes)")->check(numberCheck(Sign::NonNegative, false));
  render->add_option("--seed", ra.seed, "Random seed (0 to 2147483647, as in a scene file)")
      ->check(numberCheck(Sign::NonNegative, true, kMaxSeed));
  render->add_option("--threads", ra.threads, "Worker threads (default: all cores)")
      ->check(numberCheck(Sign::NonNegative, true) & CLI::Range(0, 4096));
  render->add_option("--integrator", ra.integrator,
                     "Integrator: pt | lt | bdpt (both wavelength families) | bdpt-shared | bdpt-independent | bdpt-mollified | ppm | "
                     "vcm (bdpt's connections and vertex merging) | vc (its connections) | bpm (its merges)")
      ->check(kIntegratorName);
  render->add_option("--mollify-bandwidth", ra.mollifyBandwidth,
                     "bdpt-mollified: wavelength kernel half-width of the first pass in nm (0: 2% of the range)")
      ->check(numberCheck(Sign::NonNegative, false));
  render->add_option("--mollify-alpha", ra.mollifyAlpha, "bdpt-mollified: bandwidth reduction alpha in (0, 1)")
      ->check(numberCheck(Sign::Positive, false) & CLI::Range(0.0, 0.999999));
  render->add_option("--ppm-direct", ra.ppmDirect,
                     "ppm: estimator of light straight from a light (render/ppm/direct): nee-elastic | nee | photons")
      ->check(CLI::IsMember({"nee-elastic", "nee", "photons"}));
  render->add_option("--ppm-nee-wavelengths", ra.ppmNeeWavelengths,
                     "ppm: wavelengths of next-event estimation's elastic lobe at the first vertex "
                     "(render/ppm/nee_wavelengths): cmf*light | camera | a one-density strategy such as mix:cmf,light")
      ->check([](const std::string& s) { return ppmNeeWavelengthsError(s); });
  render->add_option("--strategy-images", ra.strategyImages,
                     "BDPT: also write one image per (s, t) strategy (MIS-weighted) into this directory");
  render->add_flag("--strategy-unweighted", ra.strategyUnweighted, "With --strategy-images: also the unweighted images");
  render->add_option("--strategy-depth", ra.strategyDepth,
                     "With --strategy-images: longest path (scattering events) with its own images; longer ones go to deeper.exr (default 4)")
      ->check(numberCheck(Sign::NonNegative, true) & CLI::Range(0, 64));
  CLI::Option* bins = render->add_option("--spectral-bins", ra.spectralBins,
                     "Also write the spectral radiance per nm in N equal bins of the scene's wavelength range "
                     "(S0.<nm> channels, Fichet et al. 2021 layout)")
      ->check(numberCheck(Sign::Positive, true) & CLI::Range(1, kasha::SpectralBins::kMaxBins));
  render->add_option("--spectral-step", ra.spectralStep,
                     "Like --spectral-bins, bins NM wide (must divide the scene's wavelength range)")
      ->check(numberCheck(Sign::Positive, false))
      ->excludes(bins);
  const CLI::Validator strategy(
      [](std::string& s) {
        try {
          parseWavelengthSpec(s);
          return std::string();
        } catch (const std::invalid_argument& e) {
          return std::string(e.what());
        }
      },
      "STRATEGY");
  render->add_option("--sensor-sampling", ra.sensor,
                     "Camera wavelength strategy (docs/wavelength-sampling.md), e.g. cmf | uniform | light | "
                     "yamamoto=0.5 | mix:cmf,light | ms-power:cmf,light")
      ->check(strategy);
  render->add_option("--fluorescence-sampling", ra.fluorescence,
                     "Excitation wavelength at a camera path's fluorescent event (pt), e.g. material | uniform | "
                     "light | absorption | yamamoto | mix:absorption,light")
      ->check(strategy);
  render->add_option("--light-sampling", ra.light,
                     "Light subpath wavelength (lt, bdpt, bdpt-independent, ppm, vcm, vc, bpm), e.g. light | uniform | mix:light,absorption")
      ->check(strategy);
  render->add_option("--nee-sampling", ra.nee,
                     "Excitation wavelength of next-event estimation after a fluorescent event (pt): event (the "
                     "event's own) | absorption | light | uniform | yamamoto | mix:absorption,light")
      ->check(strategy);
  render->add_option("--hero", ra.hero,
                     "Wavelength lanes (hero wavelength sampling; pt, lt, ppm, every BDPT variant): wavelengths per "
                     "path, 1 (off) to 16; default 4 (1 for pt when --sensor-sampling is not one density or "
                     "--nee-sampling is not 'event')")
      ->check(CLI::Range(1, 16));
  render->add_option("--fluorescent-lanes", ra.fluorescentLanes,
                     "What wavelength lanes do at a fluorescent event (pt, lt): through (a fresh set serves every "
                     "lane before it, the default) | end (one lane kept at random goes on, as in ART and pbrt; an "
                     "experiment to compare with)")
      ->check(CLI::IsMember({"through", "end"}));
  render->add_option("--bdpt-families", ra.bdptFamilies,
                     "The light subpaths of --integrator bdpt where the scene fluoresces: auto (the default: a "
                     "pilot estimates, from both families' paths, the relative variance per sample of both and of "
                     "each family alone, and their cost in rays, and runs the most efficient; a family alone only "
                     "if it samples every path that carries light) | both | shared (= bdpt-shared) | own (= "
                     "bdpt-independent)")
      ->check(CLI::IsMember({"auto", "both", "shared", "own"}));
  render->add_option("--vcm-paths", ra.vcmPaths,
                     "The subpaths of --integrator vcm: auto (the default: a pilot estimates, from vcm's own paths, "
                     "the relative variance per sample of vcm, of vcm with the wide gather and of camera paths "
                     "alone, and their cost in rays, and runs the most efficient; camera paths alone only if they "
                     "sample every path that carries light) | bidirectional (camera and light subpaths, every "
                     "strategy) | gather (the same, with photon mapping's wide final gather: own light vertices "
                     "merge through a fluorescent lobe at the first non-specular camera vertex, and at the camera "
                     "ray's hit through its elastic lobe at their own wavelength, within 4x the radius) | camera "
                     "(camera paths alone: path tracing with next-event estimation, pt's estimator)")
      ->check(CLI::IsMember({"auto", "bidirectional", "gather", "camera"}));
  render->add_option("--sampler", ra.sampler,
                     "Random numbers of every sample: sobol (Owen-scrambled Sobol, the default) | independent (PCG32)")
      ->check(CLI::IsMember({"sobol", "independent"}));
  render->add_option("--max-depth", ra.maxDepth, "Maximum number of scattering events")->check(numberCheck(Sign::NonNegative, true));
  render->add_option("--exposure", ra.exposure, "PNG exposure in stops")
      ->check(numberCheck(Sign::Any, false) & CLI::Range(-100.0, 100.0));
  render->add_flag("-q,--quiet", ra.quiet, "No progress bar");
  render->add_option("--checkpoint", ra.checkpoint, "Write the render's state to this file periodically and at the end");
  render->add_option("--checkpoint-interval", ra.checkpointInterval, "Seconds between checkpoints (default 60; 0: every pass)")
      ->check(numberCheck(Sign::NonNegative, false));
  render->add_option("--resume", ra.resume,
                     "Continue the render saved in this checkpoint (same scene and options); keeps checkpointing to it");
  render->add_flag("--mpi", ra.mpi,
                   "Render with the ranks of an MPI job (automatic under mpirun/mpiexec/srun); rank 0 writes the outputs");
  render->add_option("--memory-limit", ra.memoryLimit, "Largest buffer kasha may allocate, e.g. 512M, 8G (default 8G)")
      ->check(kByteSize);

  MatrixArgs ma;
  CLI::App* matrix = app.add_subcommand("matrix", "Export a fluorescent material's reradiation matrix (Jung18 eq. 5) as CSV");
  matrix->add_option("scene", ma.scene, "Scene file (JSON)")->required();
  matrix->add_option("--material", ma.material, "Material name")->required();
  matrix->add_option("--step", ma.step, "Grid step in nm (default 5)")->check(numberCheck(Sign::Positive, false));
  matrix->add_option("-o,--output", ma.output, "CSV output (default: standard output)");
  matrix->add_option("--memory-limit", ma.memoryLimit, "Largest buffer kasha may allocate (default 8G)")->check(kByteSize);

  CompareArgs ca;
  CLI::App* compare = app.add_subcommand("compare", "Render with several integrators for equal time and report RMSE vs a reference");
  compare->add_option("scene", ca.scene, "Scene file (JSON)")->required();
  compare->add_option("--reference", ca.reference, "Reference OpenEXR (rendered first if it does not exist)")->required();
  compare->add_option("--integrators", ca.integrators, "Comma-separated integrators")->delimiter(',')->check(kIntegratorName);
  compare->add_option("--time", ca.time, "Seconds per integrator")->check(numberCheck(Sign::NonNegative, false));
  compare->add_option("--spp", ca.spp, "Samples per pixel per integrator")->check(numberCheck(Sign::Positive, true));
  compare->add_option("--reference-time", ca.referenceTime, "Seconds for the reference (default 60)")
      ->check(numberCheck(Sign::Positive, false));
  compare->add_option("--reference-integrator", ca.referenceIntegrator, "Integrator for the reference (default pt)")
      ->check(kIntegratorName);
  compare->add_option("--csv", ca.csv, "Write the table as CSV");
  compare->add_option("--seed", ca.seed, "Random seed (0 to 2147483647)")->check(numberCheck(Sign::NonNegative, true, kMaxSeed));
  compare->add_option("--threads", ca.threads, "Worker threads (default: all cores)")
      ->check(numberCheck(Sign::NonNegative, true));

  MetricsArgs mt;
  CLI::App* metrics = app.add_subcommand("metrics", "Print the RMSE and relMSE (XYZ) of a render against a reference as JSON");
  metrics->add_option("image", mt.image, "Rendered OpenEXR")->required();
  metrics->add_option("reference", mt.reference, "Reference OpenEXR of the same size")->required();
  metrics->add_option("--error-map", mt.errorMap, "Write the per-pixel relative squared error as a greyscale PFM");

  ExtractArgs xa;
  CLI::App* extract = app.add_subcommand(
      "extract", "Fit Zhdanov et al.'s three-part BDF to a bispectral measurement (passive, excitation, emission)");
  extract->add_option("--sample", xa.sample, "The sample's bispectral matrix (.csv or .exr)")->required();
  extract->add_option("--etalon", xa.etalon, "The non-fluorescent etalon's matrix (same grid; default: none, the "
                                             "sample is taken as etalon-normalised)");
  extract->add_option("--etalon-reflectance", xa.etalonReflectance, "The etalon's reflectance: a number or a CSV spectrum");
  extract->add_option("--epsilon", xa.epsilon, "Half-width of the near-diagonal (passive) window in nm (default 5)")
      ->check(numberCheck(Sign::NonNegative, false));
  extract->add_option("--noise-floor", xa.noiseFloor, "Fluorescent values at or below this count as 0 (default 0.002)")
      ->check(numberCheck(Sign::NonNegative, false));
  extract->add_option("--gloss", xa.gloss, "Albedo of the white gloss peak, measured separately (default 0)")
      ->check(CLI::Range(0.0, 1.0));
  extract->add_option("--gloss-exponent", xa.glossExponent, "Phong exponent of the gloss peak (default 100)")
      ->check(numberCheck(Sign::NonNegative, false));
  extract->add_option("-o,--output", xa.output, "Material file to write (.json); spectra go to <stem>_spectra.csv")
      ->required();

  try {
    app.parse(argc, argv);
    ra.integratorGiven = render->count("--integrator") > 0;
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == 0) return app.exit(e);  // --help, --version
    // A bad command line: one line, exit code 2.
    std::string msg = e.what();
    if (!render->parsed() && !matrix->parsed() && !compare->parsed() && !metrics->parsed() &&
        !extract->parsed() && argc > 1 &&
        argv[1][0] != '-')
      msg = "unknown command '" + std::string(argv[1]) + "' (expected render, compare, metrics, matrix or extract)";
    for (char& c : msg)
      if (c == '\n') c = ' ';
    std::fprintf(stderr, "kasha: error: %s (see kasha %s--help)\n", msg.c_str(),
                 render->parsed()    ? "render "
                 : matrix->parsed()  ? "matrix "
                 : compare->parsed() ? "compare "
                 : metrics->parsed() ? "metrics "
                 : extract->parsed() ? "extract "
                                     : "");
    return 2;
  }
  // Only `render` is distributed; under an MPI launcher the other commands run once per rank.
#if KASHA_WITH_MPI
  std::unique_ptr<MpiGroup> mpi;
  if (render->parsed() && (ra.mpi || launchedByMpi())) mpi = std::make_unique<MpiGroup>(&argc, &argv);
#else
  const std::unique_ptr<RenderGroup> mpi;
  if (render->parsed() && ra.mpi) {
    std::fprintf(stderr, "kasha: error: --mpi: this kasha was built without MPI (install Open MPI and reconfigure)\n");
    return 2;
  }
#endif
  // After an error on one rank the others would wait for it forever: end them all.
  auto fail = [&](const char* what, int code) {
    std::fprintf(stderr, "kasha: error: %s\n", what);
#if KASHA_WITH_MPI
    if (mpi && mpi->size() > 1) {
      std::fflush(stderr);
      mpi->abort(code);
    }
#endif
    return code;
  };
  try {
    if (render->parsed()) {
      const int code = runRender(ra, mpi.get());
      // No rank ends (and has mpirun end the job) before rank 0 has written the outputs.
#if KASHA_WITH_MPI
      if (mpi) mpi->barrier();
#endif
      return code;
    }
    if (matrix->parsed()) return runMatrix(ma);
    if (compare->parsed()) return runCompare(ca);
    if (metrics->parsed()) return runMetrics(mt);
    if (extract->parsed()) return runExtract(xa);
  } catch (const UsageError& e) {  // a command-line mistake
    return fail(e.what(), 2);
  } catch (const std::exception& e) {  // InputError included
    return fail(e.what(), 1);
  }
  return 1;
}
