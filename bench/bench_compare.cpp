// Equal-time comparison of integrators against a long path-traced reference (issue: "BDPT should
// beat PT clearly on the UV Cornell scene").
//   bench_compare [scene.json] [--resolution N] [--reference-seconds R] [--seconds T] [--seeds K]
//                 [--integrators pt,bdpt-shared,...] [--reference ref.exr] [--csv out.csv]
// The reference is rendered with the path tracer for R seconds (or read from --reference if the
// file exists, else written there); each integrator then renders for T seconds with K seeds, and
// the mean and standard deviation of its RMSE against the reference are printed and written.
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/image_output.h"
#include "scene/scene_loader.h"
#include "integrators/comparison.h"
#include "integrators/integrator_factory.h"

using namespace kasha;

int main(int argc, char** argv) {
  std::string scenePath = std::string(KASHA_SOURCE_DIR) + "/scenes/cornell_uv.json", refPath, csvPath;
  std::string list = "pt,lt,bdpt-shared,bdpt-independent";
  int res = 128, seeds = 3;
  double refSeconds = 300.0, seconds = 10.0;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto next = [&] { return std::string(i + 1 < argc ? argv[++i] : ""); };
    if (a == "--resolution") res = std::stoi(next());
    else if (a == "--reference-seconds") refSeconds = std::stod(next());
    else if (a == "--seconds") seconds = std::stod(next());
    else if (a == "--seeds") seeds = std::stoi(next());
    else if (a == "--integrators") list = next();
    else if (a == "--reference") refPath = next();
    else if (a == "--csv") csvPath = next();
    else scenePath = a;
  }
  auto scene = loadScene(scenePath);
  const Camera& c = scene->camera;
  scene->camera = Camera(c.position(), c.position() + c.forward(), Vec3(0, 1, 0), c.fovYDegrees(), res, res);

  XyzImage reference;
  if (!refPath.empty() && std::filesystem::exists(refPath)) {
    reference = readExrXyz(refPath);
    std::printf("reference        %s (read)\n", refPath.c_str());
  } else {
    const auto pt = makeIntegrator("pt", *scene, scene->render);
    Film film(res, res);
    RenderOptions opt;
    opt.spp = 1 << 30;
    opt.timeBudgetSeconds = refSeconds;
    opt.seed = 999;
    const RenderStats st = render(*scene, *pt, film, opt);
    reference = filmToXyz(film);
    if (!refPath.empty()) writeExr(film, refPath);
    std::printf("reference        pt, %.0f s, %d spp\n", st.seconds, st.spp);
  }

  std::vector<std::string> names;
  std::stringstream ss(list);
  for (std::string n; std::getline(ss, n, ',');) names.push_back(n);
  std::ofstream csv;
  if (!csvPath.empty()) {
    csv.open(csvPath);
    csv << "integrator,seconds,seed,spp,rmse,relmse\n";
  }
  std::printf("%-18s %8s %8s %12s %12s\n", "integrator", "seconds", "spp", "RMSE", "± (seeds)");
  for (const std::string& n : names) {
    double sum = 0.0, sum2 = 0.0, spp = 0.0;
    for (int k = 0; k < seeds; ++k) {
      RenderSettings settings = scene->render;
      settings.spp = 1 << 30;
      settings.timeBudgetSeconds = seconds;
      settings.seed = uint64_t(k + 1);
      const ComparisonRow row = compareIntegrators(*scene, {n}, settings, 0, reference)[0];
      sum += row.error.rmse;
      sum2 += row.error.rmse * row.error.rmse;
      spp += row.stats.spp;
      if (csv) csv << n << "," << row.stats.seconds << "," << k + 1 << "," << row.stats.spp << "," << row.error.rmse << ","
                   << row.error.relMse << "\n";
    }
    const double mean = sum / seeds, sd = seeds > 1 ? std::sqrt(std::max(0.0, (sum2 - seeds * mean * mean) / (seeds - 1))) : 0.0;
    std::printf("%-18s %8.1f %8.0f %12.5f %12.5f\n", n.c_str(), seconds, spp / seeds, mean, sd);
  }
  return 0;
}
