#include "cli/extract_command.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <sstream>
#include <iomanip>
#include <set>

#include <nlohmann/json.hpp>

#include "core/bispectral_exr.h"
#include "core/error.h"
#include "core/output_file.h"
#include "core/spectrum_csv.h"
#include "materials/zhdanov_bdf.h"
#include "materials/zhdanov_extraction.h"

namespace kasha {
namespace {

BispectralData readMatrix(const std::string& path, const char* flag) {
  const std::string ext = std::filesystem::path(path).extension().string();
  if (ext == ".csv") return readBispectralCsv(path);
  if (ext == ".exr") return readBispectralExr(path);
  throw UsageError(path, flag, "expected a .csv or .exr bispectral matrix");
}

// The piecewise-linear function through (grid, values), zero outside the grid.
float linear(const std::vector<float>& grid, const std::vector<float>& values, float l) {
  if (l < grid.front() || l > grid.back()) return 0.0f;
  const size_t k = size_t(std::upper_bound(grid.begin(), grid.end(), l) - grid.begin());
  if (k >= grid.size()) return values.back();
  const float t = (l - grid[k - 1]) / (grid[k] - grid[k - 1]);
  return (1.0f - t) * values[k - 1] + t * values[k];
}

}  // namespace

int runExtract(const ExtractArgs& a) {
  const std::filesystem::path out(a.output);
  if (out.extension() != ".json") throw UsageError(a.output, "-o", "the material file must end in .json");
  ExtractionInput in;
  in.sample = readMatrix(a.sample, "--sample");
  in.epsilon = a.epsilon;
  in.noiseFloor = a.noiseFloor;
  if (!a.etalon.empty()) {
    if (a.etalonReflectance.empty())
      throw UsageError("", "--etalon-reflectance", "required with --etalon (the etalon's known reflectance)");
    in.etalon = readMatrix(a.etalon, "--etalon");
    char* end = nullptr;
    const float constant = std::strtof(a.etalonReflectance.c_str(), &end);
    in.etalonReflectance = (end && *end == '\0' && end != a.etalonReflectance.c_str())
                               ? Spectrum::constant(constant)
                               : spectrumFromTable(readSpectralCsv(a.etalonReflectance), "").zeroOutside();
  } else if (!a.etalonReflectance.empty()) {
    throw UsageError("", "--etalon-reflectance", "given without --etalon");
  }
  const std::string csvName = out.stem().string() + "_spectra.csv";
  const std::filesystem::path csvPath = out.parent_path() / csvName;
  // The inputs have been read: neither output may replace one of them, nor each other.
  checkOutputs({{a.output, "-o", ".json", ""}, {csvPath.string(), "-o (its spectra)", ".csv", ""}});
  const ZhdanovFit fit = extractZhdanov(in);
  if (!fit.uncalibrated.empty()) {
    std::string list;
    for (const float l : fit.uncalibrated) list += (list.empty() ? "" : ", ") + std::to_string(int(std::lround(l)));
    std::fprintf(stderr, "kasha: warning: %s: inputs %s nm have no output within ±%g nm, so the etalon cannot "
                 "calibrate them: left out (no excitation there)\n", a.sample.c_str(), list.c_str(), double(a.epsilon));
  }

  // Spectra on the union grid.
  std::set<float> grid(fit.in.begin(), fit.in.end());
  grid.insert(fit.out.begin(), fit.out.end());
  std::vector<float> lambdas(grid.begin(), grid.end()), p, A, E;
  for (const float l : lambdas) {
    p.push_back(linear(fit.in, fit.passive, l));
    A.push_back(linear(fit.in, fit.excitation, l));
    E.push_back(linear(fit.out, fit.emission, l));
  }
  ZhdanovParams params;
  params.gloss = a.gloss;
  params.glossExponent = a.glossExponent;
  params.passive = Spectrum::piecewiseLinear(lambdas, p).zeroOutside();
  params.excitation = Spectrum::piecewiseLinear(lambdas, A).zeroOutside();
  params.emission = Spectrum::piecewiseLinear(lambdas, E).zeroOutside();
  const WavelengthRange range{lambdas.front(), lambdas.back()};
  if (const std::string problem = checkZhdanovParams(params, range); !problem.empty())
    throw InputError(a.sample, "", "the extracted material is not valid (" + problem +
                                       "): lower --gloss, or check the calibration (is the sample etalon-normalised, "
                                       "or does it need --etalon?)");

  {
    std::ostringstream f;
    f << "# Zhdanov et al. (2019) three-part BDF extracted by `kasha extract` from " << a.sample
      << (a.etalon.empty() ? " (taken as etalon-normalised: no etalon)" : " with etalon " + a.etalon) << "\n"
      << "# epsilon " << a.epsilon << " nm, noise floor " << a.noiseFloor << "; factorisation residual "
      << fit.residual << ", unmeasured fraction " << fit.unmeasuredFraction << "\n"
      << "# passive = p(λ) (albedo, eq. 7), excitation = A(λ) (fluorescent albedo, eq. 9), emission = E(λ) "
         "per nm with ∫E = 1 (eqs. 4, 9)\n"
      << "wavelength_nm,passive,excitation,emission\n"
      << std::setprecision(8);
    for (size_t k = 0; k < lambdas.size(); ++k) f << lambdas[k] << "," << p[k] << "," << A[k] << "," << E[k] << "\n";
    writeFileAtomically(csvPath.string(), f.str());
  }
  const auto column = [&](const char* name) {
    return nlohmann::json{{"type", "file"}, {"file", csvName}, {"column", name}, {"outside", "zero"}};
  };
  const nlohmann::json material = {{"type", "zhdanov"},
                                   {"gloss", a.gloss},
                                   {"gloss_exponent", a.glossExponent},
                                   {"passive", column("passive")},
                                   {"excitation", column("excitation")},
                                   {"emission", column("emission")}};
  writeFileAtomically(a.output, material.dump(2) + "\n");
  float maxPA = 0.0f;
  for (size_t k = 0; k < lambdas.size(); ++k) maxPA = std::max(maxPA, p[k] + A[k]);
  std::printf("%s: factorisation residual |F - E*A| / |F| = %.4f; E*A outside the measured Stokes cells: %.4f; "
              "max p + A = %.3f\nwrote %s and %s\n",
              a.sample.c_str(), fit.residual, fit.unmeasuredFraction, maxPA, a.output.c_str(), csvPath.string().c_str());
  return 0;
}

}  // namespace kasha
