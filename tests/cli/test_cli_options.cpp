// Command-line options: a bad option or value is one line "kasha: error: --option: reason" on
// stderr and exit code 2, before any file is read or written; --help and --version exit 0.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "tests/process.h"
#include "tests/expect_contains.h"

namespace kasha {
namespace {

namespace fs = std::filesystem;

class CliOptions : public ::testing::Test {
 protected:
  void SetUp() override {
    ASSERT_TRUE(fs::is_regular_file(test::kKashaBinary)) << "build the kasha target first";
    dir = (fs::path(::testing::TempDir()) / ("kasha_cli_options." + std::to_string(getpid()))).string();
    fs::create_directories(dir);
    // Not a valid scene: the options must be refused before it is read.
    scene = dir + "/scene.json";
    std::ofstream(scene) << "{}";
  }
  void TearDown() override {
    if (!HasFailure()) fs::remove_all(dir);
  }

  void expectUsageError(const std::vector<std::string>& args, const std::string& message) const {
    SCOPED_TRACE(message);
    const auto r = test::runKasha(args, dir + "/run");
    EXPECT_EQ(r.code, 2) << r.err;
    const auto lines = test::textLines(r.err);
    ASSERT_EQ(lines.size(), 1u) << r.err;
    EXPECT_EQ(lines[0].rfind("kasha: error: ", 0), 0u) << lines[0];
    EXPECT_CONTAINS(lines[0], message);
    EXPECT_TRUE(r.out.empty()) << r.out;
  }

  std::string dir, scene;
};

TEST_F(CliOptions, BadValuesExitWithCode2) {
  expectUsageError({"render", scene, "--spp", "0"}, "--spp: must be positive, got '0'");
  expectUsageError({"render", scene, "--spp", "-3"}, "--spp: must be positive, got '-3'");
  expectUsageError({"render", scene, "--spp", "2.5"}, "--spp: expected an integer, got '2.5'");
  expectUsageError({"render", scene, "--spp", "many"}, "--spp: expected a finite integer, got 'many'");
  expectUsageError({"render", scene, "--time", "nan"}, "--time: expected a finite number, got 'nan'");
  expectUsageError({"render", scene, "--time", "inf"}, "--time: expected a finite number, got 'inf'");
  expectUsageError({"render", scene, "--time", "-1"}, "--time: must not be negative, got '-1'");
  expectUsageError({"render", scene, "--seed", "-1"}, "--seed: must not be negative, got '-1'");
  expectUsageError({"render", scene, "--threads", "100000"}, "--threads");
  expectUsageError({"render", scene, "--max-depth", "-2"}, "--max-depth: must not be negative");
  expectUsageError({"render", scene, "--exposure", "nan"}, "--exposure: expected a finite number");
  expectUsageError({"render", scene, "--sensor-sampling", "spectral"}, "--sensor-sampling");
  expectUsageError({"render", scene, "--checkpoint-interval", "-5"}, "--checkpoint-interval: must not be negative");
  expectUsageError({"render", scene, "--memory-limit", "12Q"},
                   "--memory-limit: expected a size in bytes with an optional K, M, G or T suffix, got '12Q'");
  expectUsageError({"render", scene, "--memory-limit", "0"}, "--memory-limit: must be at least 1 byte");
  expectUsageError({"matrix", scene, "--material", "x", "--step", "0"}, "--step: must be positive, got '0'");
  expectUsageError({"matrix", scene, "--material", "x", "--step", "nan"}, "--step: expected a finite number");
  expectUsageError({"matrix", scene, "--material", "x", "--memory-limit", "lots"}, "--memory-limit");
}

TEST_F(CliOptions, BadCommandLinesExitWithCode2) {
  expectUsageError({}, "A subcommand is required");
  expectUsageError({"draw", scene}, "draw");
  expectUsageError({"render"}, "scene is required");
  expectUsageError({"render", scene, "--no-such-option"}, "--no-such-option");
  expectUsageError({"render", scene, "--spp"}, "--spp");
  expectUsageError({"render", scene, "--seed", "1", "--seed", "2"}, "--seed");
  expectUsageError({"matrix", scene}, "--material is required");
}

TEST_F(CliOptions, HelpAndVersion) {
  auto r = test::runKasha({"--version"}, dir + "/run");
  EXPECT_EQ(r.code, 0);
  EXPECT_CONTAINS(r.out, "kasha ");
  r = test::runKasha({"render", "--help"}, dir + "/run");
  EXPECT_EQ(r.code, 0);
  for (const char* option : {"--checkpoint", "--checkpoint-interval", "--resume", "--memory-limit"}) EXPECT_CONTAINS(r.out, option);
}

}  // namespace
}  // namespace kasha
