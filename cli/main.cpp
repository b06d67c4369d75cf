// kasha: the command-line program. `kasha render` renders a scene; `kasha matrix` exports the
// reradiation matrix of a fluorescent material (Jung18 eq. 5).
#include <CLI/CLI.hpp>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>

#include "cli/progress.h"
#include "core/error.h"
#include "core/image_output.h"
#include "core/scene_loader.h"
#include "integrators/integrator_factory.h"
#include "integrators/render_loop.h"
#include "materials/jung_bbrrdf.h"

namespace kasha {
namespace {

struct RenderArgs {
  std::string scene, output, png;
  bool noPng = false, quiet = false;
  int spp = 0, threads = 0, maxDepth = -1;
  double time = -1.0;
  int64_t seed = -1;
  std::string integrator = "pt", sensor;
  float exposure = 0.0f;
};

struct MatrixArgs {
  std::string scene, material, output;
  float step = 5.0f;
};

std::string withExtension(const std::string& path, const std::string& ext) {
  return std::filesystem::path(path).replace_extension(ext).string();
}

// Fails before any work if an output cannot be created.
void checkWritable(const std::string& path) {
  const std::filesystem::path dir = std::filesystem::absolute(path).parent_path();
  if (!std::filesystem::is_directory(dir)) throw InputError(path, "", "output directory does not exist");
  const std::string probe = (dir / ".kasha-write-test").string();
  std::ofstream f(probe);
  if (!f) throw InputError(path, "", "output directory is not writable");
  f.close();
  std::filesystem::remove(probe);
}

int runRender(const RenderArgs& a) {
  std::unique_ptr<Scene> scene = loadScene(a.scene);
  RenderSettings& r = scene->render;
  if (a.spp > 0) r.spp = a.spp;
  if (a.time >= 0.0) r.timeBudgetSeconds = a.time;
  if (a.time > 0.0 && a.spp <= 0) r.spp = 1 << 30;  // a time budget alone decides
  if (a.seed >= 0) r.seed = uint64_t(a.seed);
  if (a.maxDepth >= 0) r.maxDepth = a.maxDepth;
  if (!a.sensor.empty()) r.sensor = parseSensorSampling(a.sensor);
  std::unique_ptr<Integrator> integrator;
  try {
    integrator = makeIntegrator(a.integrator, *scene, r);
  } catch (const std::invalid_argument& e) {
    throw InputError("--integrator", "", e.what());
  }

  const std::string exr = a.output.empty() ? std::filesystem::path(a.scene).stem().string() + ".exr" : a.output;
  const std::string png = a.noPng ? "" : (a.png.empty() ? withExtension(exr, ".png") : a.png);
  const std::string stats = withExtension(exr, ".stats.json");
  checkWritable(exr);
  if (!png.empty()) checkWritable(png);

  Film film(scene->camera.width(), scene->camera.height());
  RenderOptions opt;
  opt.spp = r.spp;
  opt.timeBudgetSeconds = r.timeBudgetSeconds;
  opt.seed = r.seed;
  opt.threads = a.threads;
  ProgressBar bar(std::filesystem::path(a.scene).filename().string());
  if (!a.quiet) opt.progress = [&](int spp, double t, double total) { bar.update(spp, t, total); };
  const RenderStats st = render(*scene, *integrator, film, opt);
  bar.finish();

  writeExr(film, exr);
  if (!png.empty()) writePng(film, png, a.exposure);
  nlohmann::json j = toJson(st);
  j["scene"] = a.scene;
  j["seed"] = r.seed;
  j["sensor_sampling"] = toString(r.sensor);
  j["max_depth"] = r.maxDepth;
  j["resolution"] = {film.width(), film.height()};
  if (st.nonFiniteSamples) j["first_non_finite_pixel"] = {film.firstNonFinitePixel().first, film.firstNonFinitePixel().second};
  j["outputs"] = {{"exr", exr}, {"png", png}};
  writeTextFile(stats, j.dump(2) + "\n");
  std::printf("%s\nwrote %s%s%s, %s\n", summaryLine(st).c_str(), exr.c_str(), png.empty() ? "" : ", ", png.c_str(),
              stats.c_str());
  return 0;
}

int runMatrix(const MatrixArgs& a) {
  std::unique_ptr<Scene> scene = loadScene(a.scene);
  size_t idx = 0;
  while (idx < scene->materialNames.size() && scene->materialNames[idx] != a.material) ++idx;
  if (idx == scene->materialNames.size()) throw InputError(a.scene, "/materials/" + a.material, "no such material");
  const auto* jung = dynamic_cast<const JungBbrrdf*>(scene->materials[idx].get());
  if (!jung) throw InputError(a.scene, "/materials/" + a.material, "not a jung_fluorescent material");
  if (!(a.step > 0.0f)) throw InputError("--step", "", "must be positive");
  std::vector<float> grid;
  for (float l = scene->range.min; l <= scene->range.max + 1e-3f; l += a.step) grid.push_back(l);
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

int main(int argc, char** argv) {
  using namespace kasha;
  CLI::App app{"kasha: a bispectral renderer for fluorescence research"};
  app.set_version_flag("--version", "kasha 0.1.0");
  app.require_subcommand(1);

  RenderArgs ra;
  CLI::App* render = app.add_subcommand("render", "Render a scene to OpenEXR, PNG and a statistics JSON");
  render->add_option("scene", ra.scene, "Scene file (JSON)")->required();
  render->add_option("-o,--output", ra.output, "OpenEXR output (default: <scene name>.exr)");
  render->add_option("--png", ra.png, "PNG output (default: beside the EXR)");
  render->add_flag("--no-png", ra.noPng, "Do not write a PNG");
  render->add_option("--spp", ra.spp, "Samples per pixel (overrides the scene)")->check(CLI::PositiveNumber);
  render->add_option("--time", ra.time, "Time budget in seconds (whole passes)")->check(CLI::NonNegativeNumber);
  render->add_option("--seed", ra.seed, "Random seed")->check(CLI::NonNegativeNumber);
  render->add_option("--threads", ra.threads, "Worker threads (default: all cores)")->check(CLI::NonNegativeNumber);
  render->add_option("--integrator", ra.integrator, "Integrator: pt (path tracing) | lt (light tracing)");
  render->add_option("--sensor-sampling", ra.sensor, "Camera wavelength sampling: uniform | cmf")
      ->check(CLI::IsMember({"uniform", "cmf"}));
  render->add_option("--max-depth", ra.maxDepth, "Maximum number of scattering events")->check(CLI::NonNegativeNumber);
  render->add_option("--exposure", ra.exposure, "PNG exposure in stops");
  render->add_flag("-q,--quiet", ra.quiet, "No progress bar");

  MatrixArgs ma;
  CLI::App* matrix = app.add_subcommand("matrix", "Export a fluorescent material's reradiation matrix (Jung18 eq. 5) as CSV");
  matrix->add_option("scene", ma.scene, "Scene file (JSON)")->required();
  matrix->add_option("--material", ma.material, "Material name")->required();
  matrix->add_option("--step", ma.step, "Grid step in nm (default 5)");
  matrix->add_option("-o,--output", ma.output, "CSV output (default: standard output)");

  CLI11_PARSE(app, argc, argv);
  try {
    if (render->parsed()) return runRender(ra);
    if (matrix->parsed()) return runMatrix(ma);
  } catch (const InputError& e) {
    std::fprintf(stderr, "kasha: error: %s\n", e.what());
    return 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "kasha: error: %s\n", e.what());
    return 1;
  }
  return 1;
}
