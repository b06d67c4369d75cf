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
// Each command is its own file (cli/<command>_command.*); `render` runs the library's RenderJob
// (integrators/render_job.h), as Python's kasha.render does.
//
// `mpirun -np N kasha render ...` (detected, or --mpi) renders one image with N processes
// (cli/mpi_group.h); rank 0 writes the outputs, an error on any rank ends all with its exit code.
#include <CLI/CLI.hpp>

#include <csignal>
#include <cstdio>
#include <memory>
#include <string>

#include "cli/compare_command.h"
#include "cli/extract_command.h"
#include "cli/matrix_command.h"
#include "cli/metrics_command.h"
#include "cli/mpi_group.h"
#include "cli/option_checks.h"
#include "cli/render_command.h"
#include "core/error.h"
#include "integrators/rank_agreement.h"
#include "integrators/render_numbers.h"

int main(int argc, char** argv) {
  using namespace kasha;
  CLI::App app{"kasha: a bispectral renderer for fluorescence research"};
  app.set_version_flag("--version", "kasha 0.1.0");
  app.require_subcommand(1);

  RenderArgs ra;
  CLI::App* render = addRenderCommand(app, ra);
  MatrixArgs ma;
  CLI::App* matrix = addMatrixCommand(app, ma);

  CompareArgs ca;
  CLI::App* compare = app.add_subcommand("compare", "Render with several integrators for equal time and report RMSE vs a reference");
  compare->add_option("scene", ca.scene, "Scene file (JSON)")->required();
  compare->add_option("--reference", ca.reference, "Reference OpenEXR (rendered first if it does not exist)")->required();
  compare->add_option("--integrators", ca.integrators, "Comma-separated integrators")->delimiter(',')->check(kIntegratorName);
  compare->add_option("--time", ca.time, "Seconds per integrator")->check(numberCheck(render_numbers::kTime));
  compare->add_option("--spp", ca.spp, "Samples per pixel per integrator")->check(numberCheck(render_numbers::kSpp));
  compare->add_option("--reference-time", ca.referenceTime, "Seconds for the reference (default 60)")
      ->check(numberCheck(Sign::Positive, false));
  compare->add_option("--reference-integrator", ca.referenceIntegrator, "Integrator for the reference (default pt)")
      ->check(kIntegratorName);
  compare->add_option("--csv", ca.csv, "Write the table as CSV");
  compare->add_option("--seed", ca.seed, "Random seed (0 to 2147483647)")->check(numberCheck(render_numbers::kSeed));
  compare->add_option("--threads", ca.threads, "Worker threads (default: all cores)")
      ->check(numberCheck(render_numbers::kThreads));

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
    std::fprintf(stderr, "kasha: error: %s\n", printable(what).c_str());  // library messages may quote files
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
  } catch (const RanksDisagree& e) {  // every rank knows: rank 0 says why, and no rank is aborted
    if (e.print()) std::fprintf(stderr, "kasha: error: %s\n", e.what());
    std::fflush(stderr);
    // The first rank to exit has mpirun signal the others: they end anyway, without the stop
    // handler's line (render_command.cpp).
    std::signal(SIGTERM, SIG_IGN);
    std::signal(SIGINT, SIG_IGN);
#if KASHA_WITH_MPI
    mpi->barrier();  // no rank ends (and has mpirun end the job) before rank 0 has said why
#endif
    return 2;
  } catch (const UsageError& e) {  // a command-line mistake
    return fail(e.what(), 2);
  } catch (const std::exception& e) {  // InputError included
    return fail(e.what(), 1);
  }
  return 1;
}
