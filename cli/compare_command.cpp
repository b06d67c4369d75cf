#include "cli/compare_command.h"

#include <cstdio>
#include <filesystem>
#include <sstream>

#include "core/error.h"
#include "core/image_output.h"
#include "core/output_file.h"
#include "scene/scene_loader.h"
#include "integrators/comparison.h"
#include "integrators/render_job.h"

namespace kasha {

int runCompare(const CompareArgs& a) {
  std::unique_ptr<Scene> scene = loadScene(a.scene);
  if (a.time <= 0.0 && a.spp <= 0) throw UsageError("--time/--spp", "", "give a time budget or a sample count");
  if (a.reference.empty()) throw UsageError("--reference", "", "a reference image path is required");
  // Every render is a RenderJob (integrators/render_job.h), with its checks of the integrator's
  // settings and of memory; the budget is the same for each integrator.
  RenderSettings settings = scene->render;
  settings.spp = a.spp > 0 ? a.spp : 1 << 30;
  settings.timeBudgetSeconds = a.time;
  settings.seed = uint64_t(a.seed);
  for (const std::string& n : a.integrators) {  // combinations the integrators refuse, before any render
    try {
      RenderJobOptions check;
      check.integrator = n;
      check.settings = settings;
      RenderJob(*scene, std::move(check));
    } catch (const std::invalid_argument& e) {
      throw UsageError("--integrators " + n, "", e.what());
    }
  }
  std::vector<OutputTarget> outputs;
  if (!a.csv.empty()) outputs.push_back({a.csv, "--csv", "", ""});
  const bool renderReference = !std::filesystem::exists(a.reference);
  if (renderReference) outputs.push_back({a.reference, "--reference", ".exr", ""});
  checkOutputs(outputs);
  XyzImage reference;
  if (!renderReference) {
    reference = readExrXyz(a.reference);
    std::printf("reference: %s\n", a.reference.c_str());
  } else {
    // Render it: the given integrator for --reference-time seconds, written for reuse.
    RenderSettings r = scene->render;
    r.spp = 1 << 30;
    r.timeBudgetSeconds = a.referenceTime;
    r.seed = 0x5eed;
    RenderJobOptions ref;
    ref.integrator = a.referenceIntegrator;
    ref.settings = r;
    ref.threads = a.threads;
    RenderJob job(*scene, std::move(ref));
    job.run();
    writeExr(job.film(), a.reference);
    reference = filmToXyz(job.film());
    std::printf("reference: %s rendered with %s, %.1f s, %d spp\n", a.reference.c_str(), a.referenceIntegrator.c_str(),
                job.stats().seconds, job.stats().spp);
  }
  std::ostringstream csv;
  csv << "integrator,seconds,spp,samples_per_second,rmse,relmse\n";
  std::printf("%-18s %9s %7s %12s %12s %12s\n", "integrator", "seconds", "spp", "samples/s", "RMSE", "relMSE");
  for (const std::string& n : a.integrators) {
    const ComparisonRow r = compareIntegrators(*scene, {n}, settings, a.threads, reference)[0];
    std::printf("%-18s %9.2f %7d %12.4g %12.5g %12.5g\n", n.c_str(), r.stats.seconds, r.stats.spp,
                r.stats.samplesPerSecond, r.error.rmse, r.error.relMse);
    csv << n << "," << r.stats.seconds << "," << r.stats.spp << "," << r.stats.samplesPerSecond << ","
                 << r.error.rmse << "," << r.error.relMse << "\n";
  }
  if (!a.csv.empty()) writeFileAtomically(a.csv, csv.str());
  return 0;
}

}  // namespace kasha
