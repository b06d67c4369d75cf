// bench/convergence/run.py on a tiny report (two configurations, two sample budgets, two seeds):
// one CSV row per render whose errors are those of the library on the kept images, summary means
// and standard deviations over seeds that follow from those rows, the reference reused when it
// matches, and the report page with its figures. Needs python3 with numpy and matplotlib. The
// tiny report runs the harness three times (about 5 s each, mostly Python and matplotlib): Slow.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include "integrators/comparison.h"

namespace kasha {
namespace {

namespace fs = std::filesystem;

std::vector<std::map<std::string, std::string>> readCsv(const std::string& path) {
  std::ifstream f(path);
  std::vector<std::map<std::string, std::string>> rows;
  std::vector<std::string> header;
  for (std::string line; std::getline(f, line);) {
    std::vector<std::string> fields;
    std::stringstream ss(line);
    for (std::string v; std::getline(ss, v, ',');) fields.push_back(v);
    if (header.empty()) {
      header = fields;
      continue;
    }
    std::map<std::string, std::string> row;
    for (size_t i = 0; i < header.size() && i < fields.size(); ++i) row[header[i]] = fields[i];
    rows.push_back(row);
  }
  return rows;
}

class Harness : public ::testing::Test {
 protected:
  void SetUp() override {
    dir = (fs::path(::testing::TempDir()) / ("kasha_harness." + std::to_string(getpid()))).string();
    fs::remove_all(dir);
    fs::create_directories(dir);
    std::ofstream(dir + "/tiny.json") << R"({"render": {"max_depth": 3},
      "camera": {"position": [0, 0, -3], "look_at": [0, 0, 0], "fov": 40, "resolution": [16, 12]},
      "materials": {"grey": {"type": "lambertian", "reflectance": 0.5}},
      "shapes": [
        {"type": "rectangle", "center": [0, 0, 1], "u": [2, 0, 0], "v": [0, 2, 0], "material": "grey"},
        {"type": "sphere", "center": [0.3, 0, 0], "radius": 0.5, "material": "grey",
         "emission": {"radiance": "D65", "scale": 0.01}}]})";
    std::ofstream(dir + "/report.json") << R"({"description": "tiny", "output": "out", "work": "work",
      "threads": 1, "seeds": [1, 2], "budget": {"kind": "spp", "values": [2, 1]},
      "reference": {"integrator": "pt", "time": 0.2},
      "configurations": [{"label": "pt uniform", "integrator": "pt", "args": ["--sensor-sampling", "uniform"]},
                         {"label": "lt", "integrator": "lt"}],
      "scenes": [{"scene": "tiny.json", "crop": [0, 0, 0.5, 0.5], "reference": {"time": 0.3},
                  "comparisons": [{"combination": "pt uniform", "parts": ["lt"]}]}]})";
  }
  void TearDown() override {
    if (!HasFailure()) fs::remove_all(dir);
  }
  int runHarness() const {
    const std::string cmd = "python3 '" KASHA_SOURCE_DIR "/bench/convergence/run.py' '" + dir +
                            "/report.json' --build-dir '" KASHA_BINARY_DIR "' >'" + dir + "/log' 2>&1";
    const int status = std::system(cmd.c_str());
    return status != -1 && WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  }
  std::string log() const {
    std::ifstream f(dir + "/log");
    std::stringstream ss;
    ss << f.rdbuf();
    return ss.str();
  }
  std::string dir;
};

TEST_F(Harness, TinyReportSlow) {
  ASSERT_EQ(runHarness(), 0) << log();
  const auto runs = readCsv(dir + "/out/runs.csv");
  ASSERT_EQ(runs.size(), 2u * 2u * 2u) << "configurations × budgets × seeds";
  const XyzImage reference = readExrXyz(dir + "/work/references/tiny.exr");
  // The scene's reference time replaces the report's (0.2 s), and the record says so.
  std::ifstream record(dir + "/work/references/tiny.reference.json");
  std::stringstream recorded;
  recorded << record.rdbuf();
  EXPECT_NE(recorded.str().find("\"time\": 0.3"), std::string::npos) << recorded.str();
  std::map<std::string, std::vector<double>> relmse;  // config|budget → per seed
  for (const auto& r : runs) {
    SCOPED_TRACE(r.at("config") + " budget " + r.at("budget") + " seed " + r.at("seed"));
    EXPECT_EQ(std::stoi(r.at("spp")), std::stoi(r.at("budget"))) << "an spp budget is exact";
    const std::string label = r.at("config") == "lt" ? "lt" : "pt_uniform";
    const std::string exr = dir + "/work/tiny/" + label + "_b" + r.at("budget") + "_s" + r.at("seed") + ".exr";
    const ImageError e = compareImages(readExrXyz(exr), reference);
    EXPECT_NEAR(std::stod(r.at("rmse")), e.rmse, 1e-5 * e.rmse);
    EXPECT_NEAR(std::stod(r.at("relmse")), e.relMse, 1e-5 * e.relMse);
    relmse[r.at("config") + "|" + r.at("budget")].push_back(std::stod(r.at("relmse")));
  }
  const auto summary = readCsv(dir + "/out/summary.csv");
  ASSERT_EQ(summary.size(), 4u);
  for (const auto& s : summary) {
    const std::vector<double>& v = relmse.at(s.at("config") + "|" + s.at("budget"));
    ASSERT_EQ(v.size(), 2u);
    const double mean = (v[0] + v[1]) / 2.0, sd = std::abs(v[0] - v[1]) / std::sqrt(2.0);
    EXPECT_NEAR(std::stod(s.at("relmse_mean")), mean, 1e-5 * mean);
    EXPECT_NEAR(std::stod(s.at("relmse_std")), sd, 1e-5 * mean);
  }
  for (const char* f : {"report.md", "tiny_convergence.png", "tiny_crops.png"})
    EXPECT_TRUE(fs::is_regular_file(dir + "/out/" + f)) << f;

  // The comparison: per budget, (relMSE · time)_lt ÷ (relMSE · time)_pt uniform with the same seed,
  // mean ± sd over the two seeds.
  std::map<std::string, double> relmseTime;  // config|budget|seed
  for (const auto& r : runs)
    relmseTime[r.at("config") + "|" + r.at("budget") + "|" + r.at("seed")] =
        std::stod(r.at("relmse")) * std::stod(r.at("seconds"));
  std::ifstream page(dir + "/out/report.md");
  std::stringstream md;
  md << page.rdbuf();
  const auto table = md.str().find("**pt uniform** against its parts");
  ASSERT_NE(table, std::string::npos) << md.str();
  const auto row = md.str().find("| lt | ", table);
  ASSERT_NE(row, std::string::npos) << md.str();
  double first = 0.0, second = 0.0;
  ASSERT_EQ(std::sscanf(md.str().c_str() + row, "| lt | %lf ± %*f | %lf", &first, &second), 2) << md.str();
  auto factor = [&](const std::string& budget, const std::string& seed) {
    return relmseTime.at("lt|" + budget + "|" + seed) / relmseTime.at("pt uniform|" + budget + "|" + seed);
  };
  EXPECT_NEAR(first, (factor("1", "1") + factor("1", "2")) / 2.0, 6e-3 * first);
  EXPECT_NEAR(second, (factor("2", "1") + factor("2", "2")) / 2.0, 6e-3 * second);

  // A second run reuses the reference; a changed scene renders it again.
  const auto written = fs::last_write_time(dir + "/work/references/tiny.exr");
  ASSERT_EQ(runHarness(), 0) << log();
  EXPECT_NE(log().find("reused"), std::string::npos) << log();
  EXPECT_EQ(fs::last_write_time(dir + "/work/references/tiny.exr"), written);
  std::ofstream(dir + "/tiny.json", std::ios::app) << "\n";
  ASSERT_EQ(runHarness(), 0) << log();
  EXPECT_EQ(log().find("reused"), std::string::npos) << log();
}

// bench/convergence/region_errors.py on the tiny report's renders: a region covering the whole image
// gives each configuration the mean over seeds of run.py's relMSE at the largest budget; a region of a
// scene the report does not have is an error naming the file and the scene.
TEST_F(Harness, RegionErrorsSlow) {
  ASSERT_EQ(runHarness(), 0) << log();
  std::ofstream(dir + "/regions.json") << R"({"tiny": {"whole": [0, 0, 1, 1], "corner": [0, 0, 0.5, 0.5]}})";
  const std::string cmd = "python3 '" KASHA_SOURCE_DIR "/bench/convergence/region_errors.py' '" + dir +
                          "/report.json' '" + dir + "/regions.json' --build-dir '" KASHA_BINARY_DIR "' >'" + dir +
                          "/regions.md' 2>&1";
  ASSERT_EQ(std::system(cmd.c_str()), 0);
  std::ifstream f(dir + "/regions.md");
  std::stringstream md;
  md << f.rdbuf();
  std::map<std::string, double> mean;  // config → mean relMSE over seeds at the largest budget, 2
  for (const auto& r : readCsv(dir + "/out/runs.csv"))
    if (r.at("budget") == "2") mean[r.at("config")] += std::stod(r.at("relmse")) / 2.0;
  for (const auto& [config, expected] : mean) {
    const auto row = md.str().find("| " + config + " | ");
    ASSERT_NE(row, std::string::npos) << md.str();
    std::string cell = md.str().substr(row + config.size() + 5);  // the first region's cell
    cell.erase(0, cell.find_first_not_of('*'));                       // the best is in bold
    EXPECT_NEAR(std::stod(cell), expected, 5e-3 * expected) << config << "\n" << md.str();
  }
  std::ofstream(dir + "/regions.json") << R"({"other": {"whole": [0, 0, 1, 1]}})";
  const std::string bad = "python3 '" KASHA_SOURCE_DIR "/bench/convergence/region_errors.py' '" + dir +
                          "/report.json' '" + dir + "/regions.json' >'" + dir + "/log' 2>&1";
  const int status = std::system(bad.c_str());
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 1);
  EXPECT_NE(log().find(dir + "/regions.json: /other: no such scene"), std::string::npos) << log();
}

TEST_F(Harness, BadConfigurationNamesFileAndField) {
  std::ofstream(dir + "/report.json") << R"({"output": "out", "work": "work", "seeds": [1, 2],
      "budget": {"kind": "minutes", "values": [1]}, "reference": {"integrator": "pt", "time": 1},
      "configurations": [{"label": "a", "integrator": "pt"}], "scenes": [{"scene": "tiny.json", "crop": [0, 0, 1, 1]}]})";
  EXPECT_EQ(runHarness(), 1);
  EXPECT_NE(log().find(dir + "/report.json: /budget/kind: expected"), std::string::npos) << log();
  EXPECT_FALSE(fs::exists(dir + "/out"));
}

TEST_F(Harness, ComparisonWithAnUnknownLabelIsAnError) {
  std::ofstream(dir + "/report.json") << R"({"output": "out", "work": "work", "seeds": [1, 2],
      "budget": {"kind": "spp", "values": [1]}, "reference": {"integrator": "pt", "time": 1},
      "configurations": [{"label": "a", "integrator": "pt"}, {"label": "b", "integrator": "lt"}],
      "scenes": [{"scene": "tiny.json", "crop": [0, 0, 1, 1], "configurations": ["a"],
                  "comparisons": [{"combination": "a", "parts": ["b"]}]}]})";
  EXPECT_EQ(runHarness(), 1);
  EXPECT_NE(log().find(dir + "/report.json: /scenes/0/comparisons/0/parts/0: no configuration labelled \"b\""),
            std::string::npos)
      << log();
  EXPECT_FALSE(fs::exists(dir + "/out"));
}

}  // namespace
}  // namespace kasha
