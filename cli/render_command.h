#pragma once
// `kasha render`: reads the options, runs one RenderJob (integrators/render_job.h) and writes the
// OpenEXR, PNG, statistics and strategy images (docs/cli.md).
#include <CLI/CLI.hpp>

#include <string>
#include <vector>

#include "integrators/render_group.h"

namespace kasha {

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
  std::string sampler;
  std::vector<std::string> set;  // --set KEY=VALUE: settings of the scene's render object
  std::vector<std::string> parameters;  // -D NAME=VALUE: a Mitsuba scene's $NAME
  std::vector<std::string> searchPaths;  // -a DIR: where a Mitsuba scene's files are also looked for
  float exposure = 0.0f;
  std::string checkpoint, resume;
  double checkpointInterval = 60.0;
  std::string memoryLimit = "8G";
  std::string strategyImages;  // directory for one image per BDPT strategy
  bool strategyUnweighted = false;
  int strategyDepth = 4;
  int spectralBins = 0;        // 0: none
  double spectralStep = 0.0;   // nm; 0: none (a double: 1e-300 must not become 0)
  bool mpi = false;  // initialise MPI even if no MPI launcher is detected
};

CLI::App* addRenderCommand(CLI::App& app, RenderArgs& args);
// group: the MPI ranks rendering together, or nullptr; only rank 0 writes files and prints.
// Returns the exit code (128 + signal when stopped); throws UsageError and InputError.
int runRender(const RenderArgs& args, RenderGroup* group);

}  // namespace kasha
