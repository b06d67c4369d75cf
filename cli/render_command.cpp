#include "cli/render_command.h"

#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <atomic>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <map>

#include "cli/option_checks.h"
#include "cli/progress.h"
#include "core/checkpoint.h"
#include "core/error.h"
#include "core/image_output.h"
#include "core/input_file.h"
#include "core/memory_budget.h"
#include "core/output_file.h"
#include "integrators/integrator_factory.h"
#include "integrators/photon_mapping/direct_light_wavelengths.h"
#include "integrators/render_job.h"
#include "integrators/render_numbers.h"
#include "scene/mitsuba/mitsuba_scene.h"
#include "scene/scene_loader.h"
#include "scene/wavelength_strategy.h"

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

std::string withExtension(const std::string& path, const std::string& ext) {
  return std::filesystem::path(path).replace_extension(ext).string();
}

std::string hex(uint64_t v) {
  char buf[17];
  std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(v));
  return buf;
}

const char* signalName(int sig) { return sig == SIGINT ? "SIGINT" : sig == SIGTERM ? "SIGTERM" : "signal"; }

// The option that gave `setting` (a key of the render object or of RenderJobOptions): the --set
// that wrote it, else the option of the same name ("strategy_images" → --strategy-images).
std::string optionFor(const std::vector<RenderSetting>& set, const std::string& setting) {
  if (const RenderSetting* s = settingAt(set, renderSettingPointer(setting))) return "--set " + s->text;
  std::string option = "--" + setting;
  std::replace(option.begin(), option.end(), '_', '-');
  return option;
}

// The render job of the command line's options; its errors name the option that caused them.
std::unique_ptr<RenderJob> makeJob(const RenderArgs& a, const Scene& scene, const std::vector<RenderSetting>& set,
                                   RenderJobOptions job) {
  try {
    return std::make_unique<RenderJob>(scene, std::move(job));
  } catch (const RenderJobError& e) {
    throw UsageError(optionFor(set, e.setting), "", e.what());
  } catch (const WavelengthStrategyError& e) {
    // A command-line mistake when the command line chose the strategy or the integrator; else
    // the scene's /render settings do not fit the default integrator.
    std::string option = settingName(e.site());
    std::replace(option.begin(), option.end(), '_', '-');
    const std::map<WavelengthSite, const std::string*> given = {{WavelengthSite::Sensor, &a.sensor},
        {WavelengthSite::Fluorescence, &a.fluorescence}, {WavelengthSite::LightStart, &a.light}, {WavelengthSite::Nee, &a.nee}};
    const auto it = given.find(e.site());
    if (it != given.end() && !it->second->empty()) throw UsageError("--" + option, "", e.what());
    if (settingAt(set, "/render/" + std::string(settingName(e.site())))) throw UsageError(optionFor(set, settingName(e.site())), "", e.what());
    if (a.integratorGiven) throw UsageError("--integrator " + a.integrator, "", std::string(e.what()) + " (/render/" +
                                                                                settingName(e.site()) + " in " + a.scene + ")");
    throw InputError(a.scene, "/render/" + std::string(settingName(e.site())), e.what());
  } catch (const PpmNeeWavelengthsError& e) {
    if (settingAt(set, "/render/ppm/nee_wavelengths")) throw UsageError(optionFor(set, "ppm.nee_wavelengths"), "", e.what());
    throw InputError(a.scene, "/render/ppm/nee_wavelengths", e.what());
  } catch (const FluorescentLanesError& e) {
    if (settingAt(set, "/render/fluorescent_lanes")) throw UsageError(optionFor(set, "fluorescent_lanes"), "", e.what());
    if (!a.integratorGiven) throw InputError(a.scene, "/render/fluorescent_lanes", e.what());
    throw UsageError("--integrator " + a.integrator, "",
                     std::string(e.what()) + " (/render/fluorescent_lanes in " + a.scene + ")");
  } catch (const std::invalid_argument& e) {
    if (a.hero > 1) throw UsageError("--hero", "", e.what());
    if (!a.integratorGiven) throw InputError(a.scene, "/render/integrator", e.what());
    throw UsageError("--integrator " + a.integrator, "", e.what());
  }
}

}  // namespace

CLI::App* addRenderCommand(CLI::App& app, RenderArgs& a) {
  CLI::App* cmd = app.add_subcommand("render", "Render a scene to OpenEXR, PNG and a statistics JSON");
  cmd->add_option("scene", a.scene, "Scene file (JSON)")->required();
  cmd->add_option("-o,--output", a.output, "OpenEXR output (default: <scene name>.exr)");
  cmd->add_option("--png", a.png, "PNG output (default: beside the EXR)");
  cmd->add_flag("--no-png", a.noPng, "Do not write a PNG");
  cmd->add_option("--spp", a.spp, "Samples per pixel (overrides the scene)")->check(numberCheck(render_numbers::kSpp));
  cmd->add_option("--time", a.time, "Time budget in seconds (whole passes)")->check(numberCheck(render_numbers::kTime));
  cmd->add_option("--seed", a.seed, "Random seed (0 to 2147483647, as in a scene file)")
      ->check(numberCheck(render_numbers::kSeed));
  cmd->add_option("--threads", a.threads, "Worker threads (default: all cores)")
      ->check(numberCheck(render_numbers::kThreads));
  cmd->add_option("--integrator", a.integrator,
                  "Integrator: pt | lt | bdpt (bidirectional; render/bdpt) | ppm (photon mapping; render/ppm) | "
                  "vcm (bdpt's connections and vertex merging; render/vcm) | vc (its connections) | bpm (its merges); "
                  "bdpt-shared, bdpt-independent, bdpt-mollified stand for bdpt with render/bdpt settings")
      ->check(kIntegratorName);
  cmd->add_option("--strategy-images", a.strategyImages,
                  "BDPT: also write one image per (s, t) strategy (MIS-weighted) into this directory");
  cmd->add_flag("--strategy-unweighted", a.strategyUnweighted, "With --strategy-images: also the unweighted images");
  cmd->add_option("--strategy-depth", a.strategyDepth,
                  "With --strategy-images: longest path (scattering events) with its own images; longer ones go to deeper.exr (default 4)")
      ->check(numberCheck(render_numbers::kStrategyDepth));
  CLI::Option* bins = cmd->add_option("--spectral-bins", a.spectralBins,
                  "Also write the spectral radiance per nm in N equal bins of the scene's wavelength range "
                  "(S0.<nm> channels, Fichet et al. 2021 layout)")
      ->check(numberCheck(Sign::Positive, true) & CLI::Range(1, kasha::SpectralBins::kMaxBins));
  cmd->add_option("--spectral-step", a.spectralStep,
                  "Like --spectral-bins, bins NM wide (must divide the scene's wavelength range)")
      ->check(numberCheck(Sign::Positive, false))
      ->excludes(bins);
  const CLI::Validator strategy = parseCheck([](const std::string& s) { parseWavelengthSpec(s); }, "STRATEGY");
  cmd->add_option("--sensor-sampling", a.sensor,
                  "Camera wavelength strategy (docs/wavelength-sampling.md), e.g. cmf | uniform | light | "
                  "yamamoto=0.5 | mix:cmf,light | ms-power:cmf,light")
      ->check(strategy);
  cmd->add_option("--fluorescence-sampling", a.fluorescence,
                  "Excitation wavelength at a camera path's fluorescent event (pt), e.g. material | uniform | "
                  "light | absorption | yamamoto | mix:absorption,light")
      ->check(strategy);
  cmd->add_option("--light-sampling", a.light,
                  "Light subpath wavelength (lt, bdpt, bdpt-independent, ppm, vcm, vc, bpm), e.g. light | uniform | mix:light,absorption")
      ->check(strategy);
  cmd->add_option("--nee-sampling", a.nee,
                  "Excitation wavelength of next-event estimation after a fluorescent event (pt): event (the "
                  "event's own) | absorption | light | uniform | yamamoto | mix:absorption,light")
      ->check(strategy);
  cmd->add_option("--hero", a.hero,
                  "Wavelength lanes (hero wavelength sampling; pt, lt, ppm, every BDPT variant): wavelengths per "
                  "path, 1 (off) to 16; default 4 (1 for pt when --sensor-sampling is not one density or "
                  "--nee-sampling is not 'event')")
      ->check(CLI::Range(1, 16));
  cmd->add_option("--sampler", a.sampler,
                  "Random numbers of every sample: sobol (Owen-scrambled Sobol, the default) | independent (PCG32)")
      ->check(CLI::IsMember({"sobol", "independent"}));
  cmd->add_option("--set", a.set,
                  "KEY=VALUE, repeatable: a setting of the scene's render object (docs/scene-format.md), KEY its path, "
                  "e.g. ppm.alpha=0.7, ppm.direct=photons, bdpt.families=own, vcm.paths=camera, "
                  "fluorescent_lanes=end; VALUE is JSON if it parses, else a string")
      ->allow_extra_args(false);
  cmd->add_option("-D", a.parameters,
                  "NAME=VALUE, repeatable: a Mitsuba XML scene's parameter $NAME (before its <default>s)")
      ->allow_extra_args(false);
  cmd->add_option("-a", a.searchPaths,
                  "DIR, repeatable: a directory where a Mitsuba XML scene's files are also looked for, after its "
                  "<path>s and its own directory (Mitsuba's -a)")
      ->allow_extra_args(false);
  cmd->add_option("--max-depth", a.maxDepth, "Maximum number of scattering events")->check(numberCheck(Sign::NonNegative, true));
  cmd->add_option("--exposure", a.exposure, "PNG exposure in stops")
      ->check(numberCheck(Sign::Any, false) & CLI::Range(-100.0, 100.0));
  cmd->add_flag("-q,--quiet", a.quiet, "No progress bar");
  cmd->add_option("--checkpoint", a.checkpoint, "Write the render's state to this file periodically and at the end");
  cmd->add_option("--checkpoint-interval", a.checkpointInterval, "Seconds between checkpoints (default 60; 0: every pass)")
      ->check(numberCheck(Sign::NonNegative, false));
  cmd->add_option("--resume", a.resume,
                  "Continue the render saved in this checkpoint (same scene and options); keeps checkpointing to it");
  cmd->add_flag("--mpi", a.mpi,
                "Render with the ranks of an MPI job (automatic under mpirun/mpiexec/srun); rank 0 writes the outputs");
  cmd->add_option("--memory-limit", a.memoryLimit, "Largest buffer kasha may allocate, e.g. 512M, 8G (default 8G)")
      ->check(kByteSize);

  return cmd;
}

int runRender(const RenderArgs& given, RenderGroup* group) {
  RenderArgs a = given;  // its integrator becomes the scene's when the command line names none
  const uint64_t memoryLimit = parseByteSize(a.memoryLimit);  // validated by the option's check
  std::vector<RenderSetting> set;
  for (const std::string& text : a.set) {
    try {
      set.push_back(parseRenderSetting(text));
    } catch (const std::invalid_argument& e) {
      throw UsageError("--set " + text, "", e.what());
    }
  }
  SceneLoadOptions load;
  for (const std::string& text : a.parameters) {
    const size_t eq = text.find('=');
    const std::string name = text.substr(0, eq);
    if (eq == std::string::npos || !mitsuba::isParameterName(name))
      throw UsageError("-D " + text, "", "expected NAME=VALUE, NAME of letters, digits and '_'");
    if (!mitsuba::isMitsubaScenePath(a.scene))
      throw UsageError("-D " + text, "", "sets a parameter of a Mitsuba XML scene, not of " + a.scene);
    load.parameters[name] = text.substr(eq + 1);  // the last of one name wins
  }
  for (const std::string& dir : a.searchPaths) {
    if (const std::string problem = mitsuba::searchPathProblem(a.scene, dir); !problem.empty())
      throw UsageError("-a " + dir, "", problem);
    load.searchPaths.push_back(dir);
  }
  // What an alias stands for, once its name is known: from the command line before the scene loads
  // (whose errors may concern the alias's settings), from the scene after.
  const auto noteAlias = [&] {
    for (const IntegratorAlias& alias : integratorAliases()) {
      if (alias.name != a.integrator || (group && group->rank() != 0)) continue;
      std::string sets;
      for (const std::string& setting : alias.settings) sets += " --set " + setting;
      std::fprintf(stderr, "kasha: note: %s %s stands for --integrator %s%s\n", a.integratorGiven ? "--integrator" : "render/integrator",
                   alias.name.c_str(), alias.integrator.c_str(), sets.c_str());
    }
  };
  if (a.integratorGiven) noteAlias();
  load.memoryLimit = memoryLimit;
  load.renderSettings = set;  // checked by the loader as the scene file's own
  // Read once: the text is both loaded and hashed for checkpoints.
  const std::string sceneText = readSceneFile(a.scene);
  InputDigest inputs;  // the files the scene names
  std::unique_ptr<Scene> scene;
  try {
    const RecordInputs recording(inputs);
    scene = loadSceneFromString(sceneText, a.scene, load);
  } catch (const InputError& e) {
    if (const RenderSetting* s = settingAt(set, e.field())) throw UsageError("--set " + s->text, "", e.reason());
    throw;
  }
  RenderSettings& r = scene->render;
  if (!a.integratorGiven) {
    a.integrator = r.integrator;
    if (const std::string why = integratorNameError(a.integrator); !why.empty()) {
      if (const RenderSetting* s = settingAt(set, "/render/integrator")) throw UsageError("--set " + s->text, "", why);
      throw InputError(a.scene, "/render/integrator", why);
    }
    noteAlias();
  }
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
  if (!a.sampler.empty()) r.sampler = *parseSamplerKind(a.sampler);  // validated by the option's check
  r.memoryLimit = memoryLimit;

  RenderJobOptions o;
  o.integrator = a.integrator;
  o.settings = r;
  for (const RenderSetting& s : set) o.setKeys.push_back(s.key);
  o.threads = a.threads;
  o.spectralBins = a.spectralBins;
  o.spectralStep = a.spectralStep;
  o.strategyDepth = a.strategyImages.empty() ? -1 : a.strategyDepth;
  o.checkpoint = a.checkpoint;
  o.resume = a.resume;
  o.checkpointIntervalSeconds = a.checkpointInterval;
  // The --set options and the content of the files the scene names are part of the scene a
  // checkpoint continues, and that MPI ranks must agree on (the text alone without them).
  std::string hashed = sceneText;
  for (const RenderSetting& s : set) hashed += "\n--set " + s.text;
  for (const auto& [name, value] : load.parameters) hashed += "\n-D " + name + "=" + value;
  hashed += "\ninputs " + hex(inputs.value());
  o.sceneHash = hex(hashBytes(hashed.data(), hashed.size()));
  o.stop = &gStopSignal;
  o.group = group;
  const bool root = !group || group->rank() == 0;
  ProgressBar bar(std::filesystem::path(a.scene).filename().string());
  if (!a.quiet && root) o.progress = [&](int spp, double t, double total) { bar.update(spp, t, total); };
  const std::unique_ptr<RenderJob> job = makeJob(a, *scene, set, std::move(o));

  const std::string exr = a.output.empty() ? std::filesystem::path(a.scene).stem().string() + ".exr" : a.output;
  const std::string png = a.noPng ? "" : (a.png.empty() ? withExtension(exr, ".png") : a.png);
  const std::string stats = withExtension(exr, ".stats.json");
  const std::string& checkpoint = job->checkpoint();  // --resume's file unless --checkpoint names another
  // Every output checked before the first sample: the scene and the files it named have been read
  // by now; a checkpoint may replace the one it resumes (and only that one).
  std::vector<OutputTarget> outputs = {{exr, "-o", ".exr", ""}, {stats, "-o (its statistics)", ".json", ""}};
  if (!png.empty()) outputs.push_back({png, a.png.empty() ? "-o (its PNG)" : "--png", ".png", ""});
  if (!checkpoint.empty()) outputs.push_back({checkpoint, a.checkpoint.empty() ? "--resume" : "--checkpoint", "", a.resume});
  checkOutputs(outputs, {a.resume});
  if (!a.strategyImages.empty()) {
    std::error_code ec;
    std::filesystem::create_directories(a.strategyImages, ec);
    if (ec) throw InputError(a.strategyImages, "", "cannot create the strategy image directory: " + ec.message());
    checkOutputs({{(std::filesystem::path(a.strategyImages) / "s0_t2.exr").string(), "--strategy-images", ".exr", ""}});
  }

  installStopHandlers();
  job->run();
  bar.finish();
  const RenderStats& st = job->stats();
  // A stop request on another rank ends this one too.
  const int sig = st.stopSignal != 0 ? st.stopSignal : gStopSignal.load();
  if (!root) return sig != 0 ? 128 + sig : 0;

  writeExr(job->film(), exr, job->spectral());
  if (!png.empty()) writePng(job->film(), png, a.exposure);
  nlohmann::json j = job->statistics();
  if (sig != 0) j["signal"] = signalName(sig);
  j["outputs"] = {{"exr", exr}, {"png", png}};
  if (bidir::StrategyImages* strategies = job->strategies())
    j["outputs"]["strategy_images"] = strategies->write(a.strategyImages, a.strategyUnweighted, !png.empty(), a.exposure);
  writeTextFile(stats, j.dump(2) + "\n");
  std::printf("%s\nwrote %s%s%s, %s\n", summaryLine(st).c_str(), exr.c_str(), png.empty() ? "" : ", ", png.c_str(),
              stats.c_str());
  std::fflush(stdout);
  return sig != 0 ? 128 + sig : 0;
}

}  // namespace kasha
