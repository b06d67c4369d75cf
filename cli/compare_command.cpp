#include "cli/compare_command.h"

#include <cstdio>
#include <filesystem>
#include <sstream>

#include "core/error.h"
#include "core/image_output.h"
#include "core/output_file.h"
#include "scene/scene_loader.h"
#include "integrators/comparison.h"
#include "integrators/integrator_factory.h"

namespace kasha {

int runCompare(const CompareArgs& a) {
  std::unique_ptr<Scene> scene = loadScene(a.scene);
  if (a.time <= 0.0 && a.spp <= 0) throw UsageError("--time/--spp", "", "give a time budget or a sample count");
  if (a.reference.empty()) throw UsageError("--reference", "", "a reference image path is required");
  for (const std::string& n : a.integrators) {  // combinations the integrators refuse, before any render
    try {
      makeIntegrator(n, *scene, scene->render);
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
    const std::unique_ptr<Integrator> ref = makeIntegrator(a.referenceIntegrator, *scene, scene->render);
    Film film(scene->camera.width(), scene->camera.height());
    RenderOptions opt;
    opt.spp = 1 << 30;
    opt.timeBudgetSeconds = a.referenceTime;
    opt.seed = 0x5eed;
    opt.sampler = scene->render.sampler;
    opt.threads = a.threads;
    const RenderStats st = render(*scene, *ref, film, opt);
    writeExr(film, a.reference);
    reference = filmToXyz(film);
    std::printf("reference: %s rendered with %s, %.1f s, %d spp\n", a.reference.c_str(), a.referenceIntegrator.c_str(),
                st.seconds, st.spp);
  }
  RenderOptions opt;
  opt.spp = a.spp > 0 ? a.spp : 1 << 30;
  opt.timeBudgetSeconds = a.time;
  opt.seed = uint64_t(a.seed);
  opt.sampler = scene->render.sampler;
  opt.threads = a.threads;
  std::ostringstream csv;
  csv << "integrator,seconds,spp,samples_per_second,rmse,relmse\n";
  std::printf("%-18s %9s %7s %12s %12s %12s\n", "integrator", "seconds", "spp", "samples/s", "RMSE", "relMSE");
  for (const std::string& n : a.integrators) {
    const ComparisonRow r = compareIntegrators(*scene, {n}, opt, reference)[0];
    std::printf("%-18s %9.2f %7d %12.4g %12.5g %12.5g\n", n.c_str(), r.stats.seconds, r.stats.spp,
                r.stats.samplesPerSecond, r.error.rmse, r.error.relMse);
    csv << n << "," << r.stats.seconds << "," << r.stats.spp << "," << r.stats.samplesPerSecond << ","
                 << r.error.rmse << "," << r.error.relMse << "\n";
  }
  if (!a.csv.empty()) writeFileAtomically(a.csv, csv.str());
  return 0;
}

}  // namespace kasha
