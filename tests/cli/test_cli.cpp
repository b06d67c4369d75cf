// The `kasha` command-line program, run as a separate process: bad input gives exit code 1 and one
// line "kasha: error: ..." on stderr naming the file; a render writes its EXR, PNG and statistics;
// `kasha matrix` writes a reradiation matrix whose rows conserve energy.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/spectrum_csv.h"
#include "tests/expect_contains.h"

namespace kasha {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

const std::string kKasha = KASHA_BINARY_DIR "/kasha";

// 16×16 pixels, 2 samples per pixel: an emissive rectangle behind a sphere above a floor.
const char* kTinyScene = R"({
  "render": {"spp": 2, "max_depth": 4},
  "camera": {"position": [0, 1, -4], "look_at": [0, 1, 0], "fov": 50, "resolution": [16, 16]},
  "materials": {"white": {"type": "lambertian", "reflectance": 0.7},
                "dye": {"type": "jung_fluorescent",
                        "absorption": {"type": "gaussian", "center": 450, "fwhm": 40, "peak": 0.9},
                        "emission": {"type": "gaussian", "center": 520, "fwhm": 30},
                        "reflectance": 0.4, "c": 0.8, "Q": 0.9}},
  "shapes": [
    {"name": "floor", "type": "rectangle", "center": [0, 0, 0], "u": [0, 0, 2], "v": [2, 0, 0], "material": "white"},
    {"name": "ball", "type": "sphere", "center": [0, 1, 0], "radius": 0.7, "material": "dye"},
    {"name": "lamp", "type": "rectangle", "center": [0, 1.5, 2], "u": [1, 0, 0], "v": [0, 1, 0], "material": "white",
     "emission": {"radiance": "D65", "scale": 0.05, "two_sided": true}}
  ]
})";

struct Outcome {
  int code = -1;
  std::string out, err;
};

std::string readText(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  std::stringstream ss;
  ss << f.rdbuf();
  return ss.str();
}

std::vector<std::string> lines(const std::string& text) {
  std::vector<std::string> v;
  std::istringstream in(text);
  for (std::string l; std::getline(in, l);) v.push_back(l);
  return v;
}

class Cli : public ::testing::Test {
 protected:
  void SetUp() override {
    ASSERT_TRUE(fs::is_regular_file(kKasha))
        << "the kasha binary is not at " << kKasha
        << ": build the `kasha` target before running test_cli (tests/CMakeLists.txt should make test_cli depend on it)";
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    // The process id keeps concurrent runs (two build directories, ctest -j) apart.
    dir = (fs::path(::testing::TempDir()) / ("kasha_cli." + std::to_string(getpid())) / info->name()).string();
    fs::remove_all(dir);
    fs::create_directories(dir);
  }
  void TearDown() override {
    if (!HasFailure()) fs::remove_all(fs::path(dir).parent_path());  // kept for inspection on failure
  }

  std::string write(const std::string& name, const std::string& text) const {
    const std::string p = dir + "/" + name;
    std::ofstream(p, std::ios::binary) << text;
    return p;
  }

  // Runs `kasha <args>` from `cwd` (default: the test's directory), capturing both streams.
  Outcome kasha(const std::string& args, const std::string& cwd = "") const {
    const std::string out = dir + "/.stdout", err = dir + "/.stderr";
    const std::string cmd = "cd '" + (cwd.empty() ? dir : cwd) + "' && '" + kKasha + "' " + args + " >'" + out +
                            "' 2>'" + err + "' </dev/null";
    const int status = std::system(cmd.c_str());
    Outcome r;
    r.code = (status != -1 && WIFEXITED(status)) ? WEXITSTATUS(status) : -1;
    r.out = readText(out);
    r.err = readText(err);
    fs::remove(out);
    fs::remove(err);
    return r;
  }

  // Exit code 1 and exactly one line on stderr, "kasha: error: ...", naming `file`.
  static void expectInputError(const Outcome& r, const std::string& file, const std::string& reason) {
    EXPECT_EQ(r.code, 1) << r.err;
    const std::vector<std::string> l = lines(r.err);
    ASSERT_EQ(l.size(), 1u) << "stderr: " << r.err;
    EXPECT_EQ(l[0].rfind("kasha: error: ", 0), 0u) << l[0];
    EXPECT_CONTAINS(l[0], file);
    EXPECT_CONTAINS(l[0], reason);
  }

  std::string dir;
};

TEST_F(Cli, MissingSceneFile) {
  const std::string scene = dir + "/missing.json";
  expectInputError(kasha("render '" + scene + "' -q"), scene, "cannot open scene file");
  expectInputError(kasha("matrix '" + scene + "' --material dye"), scene, "cannot open scene file");
  EXPECT_FALSE(fs::exists(dir + "/missing.exr"));
}

TEST_F(Cli, MalformedJson) {
  const std::string scene = write("broken.json", "{\n  \"camera\": {\"fov\": 40,\n");
  expectInputError(kasha("render '" + scene + "' -q"), scene + ": malformed JSON", "parse error");
  EXPECT_FALSE(fs::exists(dir + "/broken.exr"));
}

TEST_F(Cli, UnknownField) {
  json j = json::parse(kTinyScene);
  j["materials"]["white"]["albedo"] = 0.5;
  const std::string scene = write("typo.json", j.dump(2));
  const Outcome r = kasha("render '" + scene + "' -q");
  expectInputError(r, scene, scene + ": /materials/white/albedo: unknown field");
  EXPECT_TRUE(r.out.empty()) << r.out;
  EXPECT_FALSE(fs::exists(dir + "/typo.exr"));
}

TEST_F(Cli, UnwritableOutputDirectory) {
  const std::string scene = write("tiny.json", kTinyScene);
  // A directory that does not exist.
  Outcome r = kasha("render '" + scene + "' -q -o '" + dir + "/no_such_dir/out.exr'");
  EXPECT_NE(r.code, 0);
  EXPECT_EQ(lines(r.err).size(), 1u) << r.err;
  EXPECT_CONTAINS(r.err, "kasha: error: " + dir + "/no_such_dir/out.exr");
  EXPECT_FALSE(fs::exists(dir + "/no_such_dir"));
  // A "directory" that is a regular file.
  write("plain_file", "x");
  r = kasha("render '" + scene + "' -q -o '" + dir + "/plain_file/out.exr'");
  EXPECT_NE(r.code, 0);
  EXPECT_CONTAINS(r.err, "kasha: error: ");
  // The PNG's directory is missing: nothing is written, not even the EXR.
  r = kasha("render '" + scene + "' -q -o '" + dir + "/ok.exr' --png '" + dir + "/no_such_dir/ok.png'");
  EXPECT_NE(r.code, 0);
  EXPECT_CONTAINS(r.err, dir + "/no_such_dir/ok.png");
  EXPECT_FALSE(fs::exists(dir + "/ok.exr"));
  EXPECT_FALSE(fs::exists(dir + "/ok.stats.json"));
  // A read-only directory (meaningless as root, who may write anywhere).
  if (geteuid() != 0) {
    fs::create_directories(dir + "/read_only");
    fs::permissions(dir + "/read_only", fs::perms::owner_read | fs::perms::owner_exec);
    r = kasha("render '" + scene + "' -q -o '" + dir + "/read_only/out.exr'");
    EXPECT_NE(r.code, 0);
    EXPECT_CONTAINS(r.err, "not writable");
    EXPECT_FALSE(fs::exists(dir + "/read_only/out.exr"));
    fs::permissions(dir + "/read_only", fs::perms::owner_all);
  }
  // No output, no stray write-test probe.
  std::vector<std::string> left;
  for (const auto& e : fs::recursive_directory_iterator(dir)) left.push_back(fs::relative(e.path(), dir).string());
  std::sort(left.begin(), left.end());
  std::vector<std::string> expected = {"plain_file", "tiny.json"};
  if (geteuid() != 0) expected = {"plain_file", "read_only", "tiny.json"};
  EXPECT_EQ(left, expected);
}

TEST_F(Cli, RendersATinyScene) {
  const std::string scene = write("tiny.json", kTinyScene);
  const Outcome r = kasha("render '" + scene + "' -q --threads 2 -o '" + dir + "/tiny.exr'");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_CONTAINS(r.out, "wrote " + dir + "/tiny.exr");
  for (const char* ext : {".exr", ".png", ".stats.json"}) EXPECT_TRUE(fs::is_regular_file(dir + "/tiny" + ext)) << ext;
  // File signatures.
  EXPECT_EQ(readText(dir + "/tiny.exr").substr(0, 4), std::string("\x76\x2f\x31\x01", 4));
  EXPECT_EQ(readText(dir + "/tiny.png").substr(0, 8), std::string("\x89PNG\r\n\x1a\n", 8));

  const json stats = json::parse(readText(dir + "/tiny.stats.json"));
  for (const char* key : {"seconds", "spp", "samples_per_second", "rays_per_second"}) {
    ASSERT_TRUE(stats.contains(key)) << key;
    EXPECT_TRUE(stats[key].is_number()) << key;
    EXPECT_GE(stats[key].get<double>(), 0.0) << key;
  }
  EXPECT_EQ(stats["spp"], 2);
  EXPECT_EQ(stats["samples"], 16 * 16 * 2);
  EXPECT_EQ(stats["resolution"], json({16, 16}));
  EXPECT_EQ(stats["non_finite_samples"], 0);
  EXPECT_EQ(stats["outputs"]["exr"], dir + "/tiny.exr");
  EXPECT_EQ(stats["outputs"]["png"], dir + "/tiny.png");
}

TEST_F(Cli, DefaultOutputNamesAndOverrides) {
  write("tiny.json", kTinyScene);
  // Without -o the EXR is named after the scene, in the current directory.
  const Outcome r = kasha("render tiny.json -q --threads 1 --spp 1 --seed 3 --no-png --sensor-sampling uniform");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_TRUE(fs::is_regular_file(dir + "/tiny.exr"));
  EXPECT_FALSE(fs::exists(dir + "/tiny.png"));
  const json stats = json::parse(readText(dir + "/tiny.stats.json"));
  EXPECT_EQ(stats["spp"], 1);
  EXPECT_EQ(stats["seed"], 3);
  EXPECT_EQ(stats["sensor_sampling"], "uniform");
  EXPECT_EQ(stats["max_depth"], 4);
}

TEST_F(Cli, MatrixRowsConserveEnergy) {
  const std::string scene = write("tiny.json", kTinyScene);
  const std::string csv = dir + "/dye.csv";
  const Outcome r = kasha("matrix '" + scene + "' --material dye --step 10 -o '" + csv + "'");
  ASSERT_EQ(r.code, 0) << r.err;
  ASSERT_TRUE(fs::is_regular_file(csv));
  // Comment lines, a header "wavelength_in_nm,out_360,...", then one row per input wavelength.
  const SpectralTable t = readSpectralCsv(csv);
  EXPECT_EQ(t.columns[0], "wavelength_in_nm");
  const size_t n = t.lambdas.size();
  ASSERT_EQ(n, 48u);  // 360, 370, ..., 830
  ASSERT_EQ(t.data.size(), n);
  EXPECT_EQ(t.lambdas.front(), 360.0f);
  EXPECT_EQ(t.lambdas.back(), 830.0f);
  EXPECT_EQ(t.columns[1], "out_360");
  double maxOffDiagonal = 0.0;
  for (size_t i = 0; i < n; ++i) {
    double sum = 0.0;
    for (size_t j = 0; j < n; ++j) {
      EXPECT_GE(t.data[j][i], 0.0f);
      sum += t.data[j][i];
      if (i != j) maxOffDiagonal = std::max(maxOffDiagonal, double(t.data[j][i]));
    }
    EXPECT_LE(sum, 1.0 + 1e-4) << "row " << t.lambdas[i] << " nm";
    EXPECT_GT(sum, 0.0) << "row " << t.lambdas[i] << " nm";
  }
  EXPECT_GT(maxOffDiagonal, 0.0);  // the dye fluoresces: blue in, green out
  // Blue light absorbed at 450 nm is re-emitted around 520 nm, not at 600 nm.
  const size_t in450 = 9, out520 = 16, out600 = 24;
  EXPECT_GT(t.data[out520][in450], t.data[out600][in450]);

  // To standard output when there is no -o.
  const Outcome s = kasha("matrix '" + scene + "' --material dye --step 50");
  ASSERT_EQ(s.code, 0) << s.err;
  EXPECT_CONTAINS(s.out, "wavelength_in_nm,out_360,out_410");
}

TEST_F(Cli, MatrixBadMaterial) {
  const std::string scene = write("tiny.json", kTinyScene);
  // The option's value is the mistake: exit code 2, the option and the scene named.
  Outcome r = kasha("matrix '" + scene + "' --material white");
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_CONTAINS(r.err, "kasha: error: --material: white: not a jung_fluorescent material in " + scene);
  r = kasha("matrix '" + scene + "' --material nothing");
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_CONTAINS(r.err, "kasha: error: --material: nothing: no material of that name in " + scene);
}

}  // namespace
}  // namespace kasha
