// Tabulated spectra from CSV (core/spectrum_csv.h) and the Spectrum function itself
// (core/spectrum.h): what a good file gives, and that every bad file is an InputError naming the
// file, the line and the reason.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "core/error.h"
#include "core/spectrum.h"
#include "core/spectrum_csv.h"
#include "tests/expect_contains.h"

namespace kasha {
namespace {

namespace fs = std::filesystem;

// A directory under gtest's temporary directory for this process (concurrent runs stay apart).
fs::path processDir() {
  return fs::path(::testing::TempDir()) / ("kasha_spectrum_csv." + std::to_string(getpid()));
}

// A fresh directory for the current test.
std::string tempDir() {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  const fs::path dir = processDir() / info->name();
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir.string();
}

// Removes the files of a run that passed (a failed run keeps them for inspection).
class CleanUp : public ::testing::Environment {
 public:
  void TearDown() override {
    if (!::testing::UnitTest::GetInstance()->Failed()) fs::remove_all(processDir());
  }
};
const auto* const kCleanUp = ::testing::AddGlobalTestEnvironment(new CleanUp);

std::string writeFile(const std::string& name, const std::string& text) {
  const std::string path = tempDir() + "/" + name;
  std::ofstream(path, std::ios::binary) << text;
  return path;
}

// The message of the InputError that f throws, or a failure if it throws nothing.
template <typename F>
std::string inputError(F&& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  ADD_FAILURE() << "expected an InputError";
  return "";
}

// The message of reading `text` as a CSV file and taking `column` from it.
std::string csvError(const std::string& text, const std::string& column, std::string* path) {
  *path = writeFile("bad.csv", text);
  return inputError([&] { spectrumFromTable(readSpectralCsv(*path), column); });
}

// ---------------------------------------------------------------------------------------------
// Good files

TEST(SpectralCsv, CommentsHeaderAndBlankLines) {
  const std::string path = writeFile("good.csv",
                                     "# measured 2024\n"
                                     "\n"
                                     "   # an indented comment\n"
                                     "wavelength_nm, a ,b\n"
                                     "400, 0.1, 1\n"
                                     "# a comment between rows\n"
                                     "500,0.3,2\n"
                                     "\n"
                                     "600 ,0.2,  3\n");
  const SpectralTable t = readSpectralCsv(path);
  EXPECT_EQ(t.source, path);
  ASSERT_EQ(t.columns, (std::vector<std::string>{"wavelength_nm", "a", "b"}));
  EXPECT_EQ(t.lambdas, (std::vector<float>{400.0f, 500.0f, 600.0f}));
  ASSERT_EQ(t.data.size(), 2u);
  EXPECT_EQ(t.data[0], (std::vector<float>{0.1f, 0.3f, 0.2f}));
  EXPECT_EQ(t.data[1], (std::vector<float>{1.0f, 2.0f, 3.0f}));
  EXPECT_EQ(t.lines, (std::vector<int>{5, 7, 9}));
}

TEST(SpectralCsv, CrlfLineEndings) {
  const std::string path = writeFile("crlf.csv", "# comment\r\nwavelength,value\r\n400,0.5\r\n\r\n500,0.25\r\n");
  const SpectralTable t = readSpectralCsv(path);
  ASSERT_EQ(t.columns, (std::vector<std::string>{"wavelength", "value"}));
  EXPECT_EQ(t.lambdas, (std::vector<float>{400.0f, 500.0f}));
  EXPECT_EQ(t.data[0], (std::vector<float>{0.5f, 0.25f}));
  EXPECT_EQ(t.lines, (std::vector<int>{3, 5}));
  // A CR on the last line without a final newline is stripped too.
  const SpectralTable u = parseSpectralCsv("wavelength,value\r\n400,0.5\r\n500,1\r", "mem.csv");
  EXPECT_EQ(u.data[0], (std::vector<float>{0.5f, 1.0f}));
}

TEST(SpectralCsv, ColumnSelection) {
  const SpectralTable t = parseSpectralCsv("wl,red,green,blue\n400,0.1,0.2,0.3\n500,0.4,0.5,0.6\n", "rgb.csv");
  EXPECT_FLOAT_EQ(spectrumFromTable(t, "red")(400.0f), 0.1f);
  EXPECT_FLOAT_EQ(spectrumFromTable(t, "green")(500.0f), 0.5f);
  EXPECT_FLOAT_EQ(spectrumFromTable(t, "blue")(450.0f), 0.45f);
  // With one value column the name may be left out.
  const SpectralTable one = parseSpectralCsv("wl,only\n400,0.7\n500,0.9\n", "one.csv");
  EXPECT_FLOAT_EQ(spectrumFromTable(one, "")(400.0f), 0.7f);
  EXPECT_FLOAT_EQ(spectrumFromTable(one, "only")(500.0f), 0.9f);
}

TEST(SpectralCsv, PiecewiseLinearEvaluationAndExactIntegral) {
  const SpectralTable t = parseSpectralCsv("wl,v\n400,1\n450,3\n600,0\n", "pl.csv");
  const Spectrum s = spectrumFromTable(t, "v");
  EXPECT_FLOAT_EQ(s(400.0f), 1.0f);
  EXPECT_FLOAT_EQ(s(425.0f), 2.0f);
  EXPECT_FLOAT_EQ(s(450.0f), 3.0f);
  EXPECT_FLOAT_EQ(s(500.0f), 2.0f);
  EXPECT_FLOAT_EQ(s(600.0f), 0.0f);
  // Constant extrapolation beyond the table.
  EXPECT_FLOAT_EQ(s(300.0f), 1.0f);
  EXPECT_FLOAT_EQ(s(700.0f), 0.0f);
  // Trapezoids: 50·(1+3)/2 + 150·3/2 = 100 + 225.
  EXPECT_NEAR(s.integral(400.0f, 600.0f), 325.0f, 1e-3f);
  // Plus the extrapolated ends: 50·1 on [350, 400] and nothing beyond 600.
  EXPECT_NEAR(s.integral(350.0f, 650.0f), 375.0f, 1e-3f);
  // Inside one segment: ∫ over [410, 440] of 1 + (λ−400)/25 = 30 + (40² − 10²)/50.
  EXPECT_NEAR(s.integral(410.0f, 440.0f), 60.0f, 1e-3f);
}

TEST(SpectralCsv, ScientificNotationAndSpaces) {
  const SpectralTable t = parseSpectralCsv("wl , v\n 4.0e2 , 1.5E-1 \n5e2,\t2e0\n", "sci.csv");
  EXPECT_EQ(t.columns, (std::vector<std::string>{"wl", "v"}));
  EXPECT_EQ(t.lambdas, (std::vector<float>{400.0f, 500.0f}));
  EXPECT_FLOAT_EQ(t.data[0][0], 0.15f);
  EXPECT_FLOAT_EQ(t.data[0][1], 2.0f);
}

// ---------------------------------------------------------------------------------------------
// Bad files: the message names the file, the line (where there is one) and the reason.

TEST(SpectralCsvErrors, MissingFile) {
  const std::string path = tempDir() + "/does_not_exist.csv";
  const std::string msg = inputError([&] { readSpectralCsv(path); });
  EXPECT_EQ(msg.rfind(path, 0), 0u) << msg;
  EXPECT_CONTAINS(msg, "cannot open spectrum file (No such file or directory)");
}

TEST(SpectralCsvErrors, NoHeader) {
  std::string path;
  // Only comments and blank lines: there is no line to blame.
  std::string msg = csvError("# nothing here\n\n# at all\n", "", &path);
  EXPECT_EQ(msg.rfind(path, 0), 0u) << msg;
  EXPECT_CONTAINS(msg, "no header line");
  // Numbers where the header should be: the header line is missing and the first row would
  // otherwise be lost as column names.
  msg = csvError("# data only\n400,0.5\n500,0.6\n", "", &path);
  EXPECT_CONTAINS(msg, path + ":2");
  EXPECT_CONTAINS(msg, "header");
  EXPECT_CONTAINS(msg, "missing");
  // A header with a single column.
  msg = csvError("wavelength\n400\n", "", &path);
  EXPECT_CONTAINS(msg, path + ":1");
  EXPECT_CONTAINS(msg, "needs a wavelength column and at least one value column");
  // A header and no rows.
  msg = csvError("wavelength,v\n# no rows\n", "", &path);
  EXPECT_EQ(msg.rfind(path, 0), 0u) << msg;
  EXPECT_CONTAINS(msg, "no data rows");
}

TEST(SpectralCsvErrors, RaggedRow) {
  std::string path;
  std::string msg = csvError("wl,a,b\n400,1,2\n500,1\n", "a", &path);
  EXPECT_CONTAINS(msg, path + ":3");
  EXPECT_CONTAINS(msg, "row has 2 fields, header has 3");
  msg = csvError("wl,a\n400,1\n500,1,2\n", "a", &path);
  EXPECT_CONTAINS(msg, path + ":3");
  EXPECT_CONTAINS(msg, "row has 3 fields, header has 2");
  // A trailing comma is an extra (empty) field.
  msg = csvError("wl,a\n400,1,\n", "a", &path);
  EXPECT_CONTAINS(msg, path + ":2");
  EXPECT_CONTAINS(msg, "row has 3 fields, header has 2");
}

TEST(SpectralCsvErrors, NonNumericCell) {
  std::string path;
  std::string msg = csvError("wl,a\n400,1\n500,abc\n", "a", &path);
  EXPECT_CONTAINS(msg, path + ":3");
  EXPECT_CONTAINS(msg, ": a: ");
  EXPECT_CONTAINS(msg, "'abc' is not a number");
  msg = csvError("wl,a\n400,1\n500,0.5x\n", "a", &path);  // trailing garbage
  EXPECT_CONTAINS(msg, path + ":3");
  EXPECT_CONTAINS(msg, "'0.5x' is not a number");
  msg = csvError("wl,a\n400,\n", "a", &path);  // empty cell
  EXPECT_CONTAINS(msg, path + ":2");
  EXPECT_CONTAINS(msg, "'' is not a number");
  msg = csvError("wl,a\n# c\nfour hundred,1\n", "a", &path);  // in the wavelength column
  EXPECT_CONTAINS(msg, path + ":3");
  EXPECT_CONTAINS(msg, ": wl: ");
}

TEST(SpectralCsvErrors, NonFiniteValue) {
  for (const char* bad : {"nan", "NaN", "inf", "-inf", "infinity", "1e999"}) {
    SCOPED_TRACE(bad);
    std::string path;
    const std::string msg = csvError(std::string("wl,a\n400,1\n500,") + bad + "\n", "a", &path);
    EXPECT_CONTAINS(msg, path + ":3: a: value is not finite");
  }
  std::string path;
  std::string msg = csvError("wl,a\nnan,1\n", "a", &path);
  EXPECT_CONTAINS(msg, path + ":2: wl: value is not finite");
  // Finite as a double, infinite as the 32-bit float a spectrum holds.
  msg = csvError("wl,a\n400,1\n500,1e39\n", "a", &path);
  EXPECT_CONTAINS(msg, path + ":3: a: value 1e39 is out of range of a 32-bit float");
  // Underflow is harmless: the value is (nearly) zero.
  const SpectralTable t = parseSpectralCsv("wl,a\n400,1e-400\n", "tiny.csv");
  EXPECT_EQ(t.data[0][0], 0.0f);
}

TEST(SpectralCsvErrors, NegativeValue) {
  std::string path;
  std::string msg = csvError("wl,a,b\n400,1,0\n500,-0.25,0\n600,1,0\n", "a", &path);
  EXPECT_CONTAINS(msg, path + ":3");
  EXPECT_CONTAINS(msg, ": a: ");
  EXPECT_CONTAINS(msg, "negative value -0.25");
  // Only the chosen column is checked.
  EXPECT_NO_THROW(spectrumFromTable(readSpectralCsv(path), "b"));
  // A negative or zero wavelength.
  msg = csvError("wl,a\n-400,1\n", "a", &path);
  EXPECT_CONTAINS(msg, path + ":2");
  EXPECT_CONTAINS(msg, "wavelength must be positive");
}

TEST(SpectralCsvErrors, UnsortedAndDuplicateWavelengths) {
  std::string path;
  std::string msg = csvError("wl,a\n400,1\n500,1\n450,1\n", "a", &path);
  EXPECT_CONTAINS(msg, path + ":4");
  EXPECT_CONTAINS(msg, "strictly increasing");
  msg = csvError("wl,a\n400,1\n# dup\n400,2\n", "a", &path);
  EXPECT_CONTAINS(msg, path + ":4");
  EXPECT_CONTAINS(msg, "strictly increasing");
}

TEST(SpectralCsvErrors, UnknownColumn) {
  std::string path;
  const std::string msg = csvError("wl,red,green\n400,1,1\n", "blue", &path);
  EXPECT_EQ(msg.rfind(path, 0), 0u) << msg;
  EXPECT_CONTAINS(msg, "column");
  EXPECT_CONTAINS(msg, "no column named 'blue'");
  // The wavelength column is not a value column.
  EXPECT_CONTAINS(csvError("wl,red\n400,1\n", "wl", &path), "no column named 'wl'");
}

TEST(SpectralCsvErrors, AmbiguousColumn) {
  std::string path;
  const std::string msg = csvError("wl,red,green\n400,1,1\n", "", &path);
  EXPECT_EQ(msg.rfind(path, 0), 0u) << msg;
  EXPECT_CONTAINS(msg, "column");
  EXPECT_CONTAINS(msg, "2 value columns; name one");
}

// ---------------------------------------------------------------------------------------------
// Spectrum

TEST(Spectrum, Constant) {
  const Spectrum s = Spectrum::constant(0.75f);
  EXPECT_FLOAT_EQ(s(200.0f), 0.75f);
  EXPECT_FLOAT_EQ(s(2000.0f), 0.75f);
  EXPECT_NEAR(s.integral(400.0f, 500.0f), 75.0f, 1e-3f);
  EXPECT_EQ(s.integral(500.0f, 400.0f), 0.0f);  // reversed limits
  EXPECT_FLOAT_EQ(Spectrum()(550.0f), 0.0f);
}

TEST(Spectrum, BoxIsAStep) {
  const Spectrum b = Spectrum::box(400.0f, 500.0f, 2.0f);  // 2 on [400, 500)
  EXPECT_EQ(b(300.0f), 0.0f);
  EXPECT_EQ(b(399.99f), 0.0f);
  EXPECT_EQ(b(400.0f), 2.0f);
  EXPECT_EQ(b(450.0f), 2.0f);
  EXPECT_EQ(b(499.99f), 2.0f);
  EXPECT_EQ(b(500.0f), 0.0f);
  EXPECT_EQ(b(600.0f), 0.0f);
  EXPECT_NEAR(b.integral(300.0f, 700.0f), 200.0f, 1e-3f);
  EXPECT_NEAR(b.integral(400.0f, 500.0f), 200.0f, 1e-3f);
  EXPECT_NEAR(b.integral(450.0f, 550.0f), 100.0f, 1e-3f);
  EXPECT_NEAR(b.integral(350.0f, 425.0f), 50.0f, 1e-3f);
  EXPECT_NEAR(b.integral(420.0f, 430.0f), 20.0f, 1e-3f);
  EXPECT_EQ(b.integral(500.0f, 700.0f), 0.0f);
  EXPECT_EQ(b.maxValue(300.0f, 700.0f), 2.0f);
  EXPECT_EQ(b.minValue(300.0f, 700.0f), 0.0f);
}

TEST(Spectrum, GaussianFwhm) {
  const float centre = 550.0f, fwhm = 40.0f, peak = 3.0f;
  const Spectrum g = Spectrum::gaussian(centre, fwhm, peak);
  EXPECT_NEAR(g(centre), peak, 1e-4f);
  EXPECT_NEAR(g(centre - 0.5f * fwhm), 0.5f * peak, 0.01f * 0.5f * peak);
  EXPECT_NEAR(g(centre + 0.5f * fwhm), 0.5f * peak, 0.01f * 0.5f * peak);
  EXPECT_LT(g(centre + 0.6f * fwhm), 0.5f * peak);
  EXPECT_GT(g(centre - 0.4f * fwhm), 0.5f * peak);
  // Zero beyond ±3 FWHM.
  EXPECT_EQ(g(centre + 3.01f * fwhm), 0.0f);
  EXPECT_EQ(g(centre - 3.01f * fwhm), 0.0f);
  // ∫ = peak·σ·√(2π) with σ = FWHM / (2√(2 ln 2)).
  const double sigma = fwhm / (2.0 * std::sqrt(2.0 * std::log(2.0)));
  const double expected = peak * sigma * std::sqrt(2.0 * 3.14159265358979);
  EXPECT_NEAR(g.integral(300.0f, 800.0f), expected, 1e-3 * expected);
}

TEST(Spectrum, BlackbodyPeakFollowsWien) {
  for (float kelvin : {4000.0f, 5000.0f, 5778.0f, 6500.0f}) {
    SCOPED_TRACE(kelvin);
    const Spectrum b = Spectrum::blackbody(kelvin);
    float best = 0.0f, bestLambda = 0.0f;
    for (float l = 300.0f; l <= 830.0f; l += 0.1f)
      if (b(l) > best) best = b(l), bestLambda = l;
    EXPECT_NEAR(bestLambda, 2.898e6f / kelvin, 2.0f);
    EXPECT_NEAR(best, 1.0f, 1e-4f);  // normalised to 1 at its maximum over 300–830 nm
  }
  // Below ~3500 K the maximum lies beyond 830 nm: the curve rises across the visible range.
  const Spectrum warm = Spectrum::blackbody(2700.0f);
  EXPECT_LT(warm(450.0f), warm(650.0f));
  EXPECT_NEAR(warm(830.0f), 1.0f, 1e-4f);
}

TEST(Spectrum, ZeroOutside) {
  const Spectrum s = Spectrum::piecewiseLinear({400.0f, 500.0f}, {1.0f, 2.0f});
  EXPECT_FLOAT_EQ(s(300.0f), 1.0f);  // constant extrapolation
  EXPECT_FLOAT_EQ(s(600.0f), 2.0f);
  EXPECT_NEAR(s.integral(300.0f, 700.0f), 100.0f + 150.0f + 400.0f, 1e-2f);
  const Spectrum z = s.zeroOutside();
  EXPECT_EQ(z(399.9f), 0.0f);
  EXPECT_FLOAT_EQ(z(400.0f), 1.0f);
  EXPECT_FLOAT_EQ(z(450.0f), 1.5f);
  EXPECT_NEAR(z(499.9f), 2.0f, 1e-2f);
  EXPECT_EQ(z(500.1f), 0.0f);
  EXPECT_EQ(z(700.0f), 0.0f);
  EXPECT_NEAR(z.integral(300.0f, 700.0f), 150.0f, 1e-2f);
  EXPECT_NEAR(z.integral(400.0f, 500.0f), 150.0f, 1e-2f);
}

TEST(Spectrum, Scaled) {
  const Spectrum s = Spectrum::piecewiseLinear({400.0f, 500.0f, 600.0f}, {0.0f, 1.0f, 0.5f});
  const Spectrum t = s.scaled(3.0f);
  for (float l : {350.0f, 400.0f, 450.0f, 500.0f, 575.0f, 700.0f}) EXPECT_FLOAT_EQ(t(l), 3.0f * s(l)) << l;
  EXPECT_NEAR(t.integral(380.0f, 650.0f), 3.0f * s.integral(380.0f, 650.0f), 1e-3f);
  EXPECT_EQ(s(450.0f), 0.5f);  // the original is unchanged
}

TEST(Spectrum, IntegralOverPartialRange) {
  const Spectrum tri = Spectrum::piecewiseLinear({400.0f, 500.0f, 600.0f}, {0.0f, 1.0f, 0.0f});
  EXPECT_NEAR(tri.integral(400.0f, 600.0f), 100.0f, 1e-3f);
  EXPECT_NEAR(tri.integral(450.0f, 550.0f), 75.0f, 1e-3f);   // 2 · (0.5 + 1)/2 · 50
  EXPECT_NEAR(tri.integral(350.0f, 450.0f), 12.5f, 1e-3f);   // 0.5 · 0.5 · 50
  EXPECT_NEAR(tri.integral(500.0f, 500.0f), 0.0f, 1e-6f);
  EXPECT_NEAR(tri.integral(425.0f, 475.0f), 25.0f, 1e-3f);   // within one segment: mean 0.5 · 50
  // A step in the middle: the integral takes the left limit up to it and the right value after.
  const Spectrum step = Spectrum::piecewiseLinear({400.0f, 500.0f, 500.0f, 600.0f}, {1.0f, 1.0f, 3.0f, 3.0f});
  EXPECT_FLOAT_EQ(step(500.0f), 3.0f);
  EXPECT_NEAR(step.integral(450.0f, 500.0f), 50.0f, 1e-3f);
  EXPECT_NEAR(step.integral(500.0f, 550.0f), 150.0f, 1e-3f);
  EXPECT_NEAR(step.integral(450.0f, 550.0f), 200.0f, 1e-3f);
}


// Linear interpolation by a scan of the knots, the test's own (constant beyond the ends).
float interpolateByScan(const std::vector<float>& x, const std::vector<float>& y, float l) {
  if (l <= x.front()) return y.front();
  for (size_t i = 0; i + 1 < x.size(); ++i)
    if (l < x[i + 1]) return y[i] + (l - x[i]) / (x[i + 1] - x[i]) * (y[i + 1] - y[i]);
  return y.back();
}

TEST(Spectrum, EquallySpacedKnotsThenAnOddOneInterpolate) {
  // 400 ... 700 every 100 nm, then a last knot 0.01 nm on (as a table closed by a near-step): the
  // equally spaced run and the rest are both the piecewise-linear function of the knots.
  const std::vector<float> x{400.0f, 500.0f, 600.0f, 700.0f, 700.01f}, y{0.5f, 2.0f, 1.0f, 3.0f, 0.25f};
  const Spectrum s = Spectrum::piecewiseLinear(x, y);
  for (float l = 350.0f; l <= 750.0f; l += 0.37f) EXPECT_NEAR(s(l), interpolateByScan(x, y, l), 1e-5f) << l;
  EXPECT_NEAR(s(700.005f), interpolateByScan(x, y, 700.005f), 1e-3f);
  // A run broken in the middle: 400, 410, 420, then 500, 510.
  const std::vector<float> x2{400.0f, 410.0f, 420.0f, 500.0f, 510.0f}, y2{1.0f, 0.0f, 2.0f, 4.0f, 1.0f};
  const Spectrum s2 = Spectrum::piecewiseLinear(x2, y2);
  for (float l = 390.0f; l <= 520.0f; l += 0.23f) EXPECT_NEAR(s2(l), interpolateByScan(x2, y2, l), 1e-5f) << l;
}

TEST(Spectrum, MinimumIsTheInfimumOverAllWavelengths) {
  const Spectrum s = Spectrum::piecewiseLinear({400.0f, 500.0f, 500.0f, 600.0f}, {0.7f, 0.3f, 0.9f, 0.5f});
  // Its infimum: 0.3, the left limit at the step (never taken, approached from the left).
  float least = s(300.0f);
  for (float l = 300.0f; l <= 700.0f; l += 0.1f) {
    EXPECT_LE(s.minimum(), s(l)) << l;
    least = std::min(least, s(l));
  }
  EXPECT_NEAR(s.minimum(), least, 1e-3f);
  EXPECT_EQ(Spectrum::box(450.0f, 550.0f, 2.0f).minimum(), 0.0f);
  EXPECT_EQ(Spectrum::constant(0.25f).minimum(), 0.25f);
}

}  // namespace
}  // namespace kasha
