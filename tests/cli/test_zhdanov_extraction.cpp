// Zhdanov et al.'s extraction (materials/zhdanov_extraction.h, §4–7, eqs. 5–9) on synthetic
// measurements generated from known p, A and E — with and without an etalon, with the
// monochromator's spread around the diagonal and an unknown lamp spectrum — and `kasha extract`
// end to end: the material file it writes loads and reproduces the known parameters.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <functional>

#include "core/bispectral_data.h"
#include "core/error.h"
#include "materials/material_json.h"
#include "materials/zhdanov_bdf.h"
#include "materials/zhdanov_extraction.h"
#include "tests/process.h"

namespace kasha {
namespace {

// Known parameters: A on 300–460 nm, E on 500–700 nm (no overlap, so the factorised fluorescence
// lies entirely on the Stokes side and the recipe is exact), a sloped passive part.
double trueP(double l) { return 0.2 + 0.6 * (l - 300.0) / 480.0; }
double trueA(double l) { return l <= 460.0 ? 0.3 * std::exp(-std::pow((l - 380.0) / 40.0, 2.0)) : 0.0; }
double eShape(double l) { return l > 500.0 && l < 700.0 ? std::pow(std::sin(kPi * (l - 500.0) / 200.0), 2.0) : 0.0; }

struct Synthetic {
  BispectralData sample, etalon;
  std::vector<double> E;  // per nm at the output grid, Σ E·10 = 1
};

// The fluorimeter of Zhdanov §4: raw = C·I(λ_i)·[p·F_1 + F̄_1·f^(f)] with the monochromator's
// band F_1 spread over the diagonal band and its two neighbours (weights `spread`), lamp I(λ_i) and
// a constant sensor scale C; the etalon of reflectance ρ_e through the same instrument (eq. 6).
Synthetic makeSynthetic(const std::function<double(double, double)>& extraFluorescence = nullptr,
                        float firstOutput = 290.0f) {
  Synthetic s;
  for (float l = 300.0f; l <= 780.0f; l += 10.0f) s.sample.in.push_back(l);
  for (float l = firstOutput; l <= 790.0f; l += 10.0f) s.sample.out.push_back(l);
  s.sample.source = "synthetic_sample";
  s.sample.value.assign(s.sample.in.size() * s.sample.out.size(), 0.0f);
  s.etalon = s.sample;
  s.etalon.source = "synthetic_etalon";
  double mass = 0.0;
  for (const float l : s.sample.out) mass += eShape(l) * 10.0;
  for (const float l : s.sample.out) s.E.push_back(eShape(l) / mass);
  const double C = 37.0, spread[3] = {0.2, 0.6, 0.2};
  const auto lamp = [](double l) { return 0.5 + std::exp(-std::pow((l - 450.0) / 120.0, 2.0)); };
  const auto rhoE = [](double l) { return 0.9 + 0.05 * (l - 300.0) / 480.0; };
  for (size_t i = 0; i < s.sample.in.size(); ++i)
    for (size_t o = 0; o < s.sample.out.size(); ++o) {
      const double li = s.sample.in[i], lo = s.sample.out[o];
      const int d = int(std::lround((lo - li) / 10.0));
      const double f1 = std::abs(d) <= 1 ? spread[d + 1] : 0.0;
      double fl = trueA(li) * s.E[o] * 10.0;  // band value of A·E
      if (extraFluorescence) fl += extraFluorescence(li, lo) * 10.0;
      s.sample.at(o, i) = float(C * lamp(li) * (trueP(li) * f1 + fl));
      s.etalon.at(o, i) = float(C * lamp(li) * rhoE(li) * f1);
    }
  return s;
}

ExtractionInput inputFor(const Synthetic& s, bool withEtalon) {
  ExtractionInput in;
  in.sample = s.sample;
  if (withEtalon) {
    in.etalon = s.etalon;
    std::vector<float> l, v;
    for (float x = 300.0f; x <= 780.0f; x += 10.0f) {
      l.push_back(x);
      v.push_back(float(0.9 + 0.05 * (x - 300.0) / 480.0));
    }
    in.etalonReflectance = Spectrum::piecewiseLinear(l, v);
  }
  in.epsilon = 10.0f;  // the diagonal band and its two neighbours
  return in;
}

void expectRecovered(const ZhdanovFit& fit, const Synthetic& s, double pScale) {
  for (size_t i = 0; i < fit.in.size(); ++i) {
    const double l = fit.in[i];
    if (fit.passiveMeasured[i]) EXPECT_NEAR(fit.passive[i], pScale * trueP(l), 0.01 * pScale * trueP(l)) << l;
    EXPECT_NEAR(fit.excitation[i], trueA(l), 0.01 * 0.3) << l;  // 1% of A's peak
  }
  double eMax = 0.0;
  for (const double e : s.E) eMax = std::max(eMax, e);
  for (size_t o = 0; o < fit.out.size(); ++o) EXPECT_NEAR(fit.emission[o], s.E[o], 0.01 * eMax) << fit.out[o];
}

TEST(ZhdanovExtraction, RecoversKnownPartsThroughAnEtalon) {
  const Synthetic s = makeSynthetic();
  const ZhdanovFit fit = extractZhdanov(inputFor(s, true));
  expectRecovered(fit, s, 1.0);
  EXPECT_LT(fit.residual, 1e-4);
  EXPECT_LT(fit.unmeasuredFraction, 1e-6);
}

TEST(ZhdanovExtraction, EtalonNormalisedInputNeedsNoEtalon) {
  // Divide the raw sample by the etalon's calibration by hand: R / (C·I(λ_i)).
  Synthetic s = makeSynthetic();
  for (size_t i = 0; i < s.sample.in.size(); ++i) {
    double cal = 0.0;
    for (size_t o = 0; o < s.sample.out.size(); ++o) cal += s.etalon.at(o, i);
    const double rho = 0.9 + 0.05 * (s.sample.in[i] - 300.0) / 480.0;
    for (size_t o = 0; o < s.sample.out.size(); ++o) s.sample.at(o, i) = float(s.sample.at(o, i) / (cal / rho));
  }
  expectRecovered(extractZhdanov(inputFor(s, false)), s, 1.0);
}

TEST(ZhdanovExtraction, InputsWithoutANearbyOutputAreReportedNotGuessed) {
  // The Post-it layout: outputs from 380 nm only, so an etalon cannot calibrate the UV inputs.
  const Synthetic s = makeSynthetic(nullptr, 380.0f);
  const ZhdanovFit fit = extractZhdanov(inputFor(s, true));
  ASSERT_FALSE(fit.uncalibrated.empty());
  EXPECT_EQ(fit.uncalibrated.front(), 300.0f);
  EXPECT_EQ(fit.uncalibrated.back(), 360.0f);
  for (size_t i = 0; i < fit.in.size(); ++i)
    if (fit.in[i] <= 360.0f) EXPECT_EQ(fit.excitation[i], 0.0f);
}

TEST(ZhdanovExtraction, ResidualGrowsWhenTheFactorisationFails) {
  // A second fluorophore excited at 400–520 nm emitting at 560–760 nm: F is then rank 2.
  double previous = -1.0;
  for (const double k : {0.0, 0.05, 0.2}) {
    const auto second = [k](double li, double lo) {
      const double a = li >= 400.0 && li <= 520.0 ? k : 0.0;
      return lo > 560.0 && lo < 760.0 ? a / 200.0 : 0.0;
    };
    const ZhdanovFit fit = extractZhdanov(inputFor(makeSynthetic(second), true));
    EXPECT_GT(fit.residual, previous) << k;
    previous = fit.residual;
  }
  EXPECT_GT(previous, 0.1);
}

TEST(ZhdanovExtraction, MismatchedEtalonIsAnError) {
  const Synthetic s = makeSynthetic();
  ExtractionInput in = inputFor(s, true);
  in.etalon->in.pop_back();
  EXPECT_THROW(extractZhdanov(in), InputError);
  in = inputFor(s, true);
  std::fill(in.etalon->value.begin(), in.etalon->value.end(), 0.0f);
  try {
    extractZhdanov(in);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("synthetic_etalon"), std::string::npos) << e.what();
  }
}

TEST(ZhdanovExtraction, CommandWritesALoadableMaterial) {
  const Synthetic s = makeSynthetic();
  const auto dir = std::filesystem::temp_directory_path() / "kasha_extract_test";
  std::filesystem::create_directories(dir);
  writeBispectralCsv((dir / "sample.csv").string(), s.sample, "synthetic sample");
  writeBispectralCsv((dir / "etalon.csv").string(), s.etalon, "synthetic etalon");
  const std::string out = (dir / "fit.json").string();
  const test::Finished r = test::runKasha({"extract", "--sample", (dir / "sample.csv").string(), "--etalon",
                                           (dir / "etalon.csv").string(), "--etalon-reflectance", "0.92", "--epsilon",
                                           "10", "--noise-floor", "0", "-o", out},
                                          (dir / "run").string());
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("factorisation residual"), std::string::npos) << r.out;
  SpectrumContext ctx("scene.json", dir.string());
  const WavelengthRange range{300.0f, 830.0f};
  const std::unique_ptr<Material> m = parseMaterial({{"type", "file"}, {"file", "fit.json"}}, ctx, "/materials/fit", range);
  const auto* z = dynamic_cast<const ZhdanovBdf*>(m.get());
  ASSERT_TRUE(z);
  // A constant etalon reflectance of 0.92 instead of the true 0.9–0.95 scales p and A by 0.92/ρ_e.
  for (float l = 300.0f; l <= 460.0f; l += 10.0f) {
    const double scale = 0.92 / (0.9 + 0.05 * (l - 300.0) / 480.0);
    if (l >= 370.0f) EXPECT_NEAR(z->passive(l), scale * trueP(l), 0.01 * trueP(l)) << l;
    if (l >= 370.0f) EXPECT_NEAR(z->A(l), scale * trueA(l), 0.003) << l;
  }
  double eMax = 0.0;
  for (const double e : s.E) eMax = std::max(eMax, e);
  for (size_t o = 0; o < s.sample.out.size(); ++o) EXPECT_NEAR(z->E(s.sample.out[o]), s.E[o], 0.01 * eMax);
  // Bad input: exit 1, the file named.
  const test::Finished bad = test::runKasha({"extract", "--sample", (dir / "none.csv").string(), "-o", out},
                                            (dir / "bad").string());
  EXPECT_EQ(bad.code, 1);
  EXPECT_NE(bad.err.find("none.csv"), std::string::npos) << bad.err;
  const std::string sample = (dir / "sample.csv").string();
  // Command-line mistakes exit with 2, a measurement the fit cannot use with 1.
  struct Case {
    std::vector<std::string> args;
    std::string expected;
    int code;
  };
  for (const auto& [args, expected, code] : std::vector<Case>{
           {{"extract", "--sample", sample, "--etalon", sample, "-o", out}, "--etalon-reflectance", 2},
           {{"extract", "--sample", sample, "--etalon-reflectance", "0.9", "-o", out}, "without --etalon", 2},
           {{"extract", "--sample", sample, "-o", (dir / "fit.txt").string()}, ".json", 2},
           {{"extract", "--sample", (dir / "sample.txt").string(), "-o", out}, ".csv or .exr", 2},
           {{"extract", "--sample", sample, "-o", sample}, "must end in .json", 2},
           {{"extract", "--sample", sample, "-o", out}, "--etalon?", 1}}) {
    const test::Finished e = test::runKasha(args, (dir / "err").string());
    EXPECT_EQ(e.code, code) << expected << ": " << e.err;
    EXPECT_NE(e.err.find(expected), std::string::npos) << expected << ": " << e.err;
  }
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace kasha
