// `kasha metrics IMAGE REFERENCE`: the RMSE and relMSE it prints are those of the comparison
// library (integrators/comparison.h) on the images read back from the EXR files, its error map
// averages to the relMSE, and bad input (a missing file, images of different sizes) exits 1
// naming the file.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>

#include <nlohmann/json.hpp>

#include "integrators/comparison.h"
#include "tests/process.h"

namespace kasha {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

XyzImage randomImage(int w, int h, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(0.0f, 2.0f);
  XyzImage img{w, h, {}};
  for (int i = 0; i < w * h; ++i) img.pixels.push_back(Vec3(u(rng), u(rng), u(rng)));
  return img;
}

// The definitions of ImageError, summed channel by channel.
TEST(Metrics, MatchTheirDefinitions) {
  const XyzImage a = randomImage(5, 3, 1), b = randomImage(5, 3, 2);
  double se = 0.0, rel = 0.0;
  for (size_t i = 0; i < a.pixels.size(); ++i)
    for (int c = 0; c < 3; ++c) {
      const double d = double(a.pixels[i][c]) - double(b.pixels[i][c]);
      se += d * d;
      rel += d * d / (double(b.pixels[i][c]) * b.pixels[i][c] + 1e-2);
    }
  const ImageError e = compareImages(a, b);
  EXPECT_NEAR(e.rmse, std::sqrt(se / 45.0), 1e-12);
  EXPECT_NEAR(e.relMse, rel / 45.0, 1e-12);
  const std::vector<float> map = relativeErrorMap(a, b);
  ASSERT_EQ(map.size(), 15u);
  double mean = 0.0;
  for (float v : map) mean += v / 15.0;
  EXPECT_NEAR(mean, e.relMse, 1e-6 * e.relMse);
  const ImageError zero = compareImages(a, a);
  EXPECT_EQ(zero.rmse, 0.0);
  EXPECT_EQ(zero.relMse, 0.0);
  EXPECT_THROW(compareImages(a, randomImage(3, 5, 3)), std::invalid_argument);
  EXPECT_THROW(relativeErrorMap(a, randomImage(5, 4, 3)), std::invalid_argument);
}

// A 12×8 glowing sphere in front of a grey wall.
std::string tinyScene(int width) {
  return R"({"render": {"spp": 2, "max_depth": 3},
  "camera": {"position": [0, 0, -3], "look_at": [0, 0, 0], "fov": 40, "resolution": [)" +
         std::to_string(width) + R"(, 8]},
  "materials": {"grey": {"type": "lambertian", "reflectance": 0.5}},
  "shapes": [
    {"type": "rectangle", "center": [0, 0, 1], "u": [2, 0, 0], "v": [0, 2, 0], "material": "grey"},
    {"type": "sphere", "center": [0.3, 0, 0], "radius": 0.5, "material": "grey",
     "emission": {"radiance": "D65", "scale": 0.01}}]})";
}

class MetricsCli : public ::testing::Test {
 protected:
  void SetUp() override {
    ASSERT_TRUE(fs::is_regular_file(test::kKashaBinary)) << "build the kasha target first";
    dir = (fs::path(::testing::TempDir()) / ("kasha_metrics." + std::to_string(getpid()))).string();
    fs::create_directories(dir);
  }
  void TearDown() override {
    if (!HasFailure()) fs::remove_all(dir);
  }
  // Runs kasha with `args`; returns the exit code, stdout and stderr.
  int run(const std::vector<std::string>& args, std::string* out = nullptr, std::string* err = nullptr) const {
    const test::Child c = test::spawnKasha(args, dir + "/run");
    const int status = test::waitChild(c, 60.0);
    if (out) *out = test::readTextFile(c.out);
    if (err) *err = test::readTextFile(c.err);
    return (status != -1 && WIFEXITED(status)) ? WEXITSTATUS(status) : -1;
  }
  std::string renderTiny(int width, int seed) const {
    const std::string scene = dir + "/tiny" + std::to_string(width) + ".json";
    std::ofstream(scene) << tinyScene(width);
    const std::string exr = dir + "/w" + std::to_string(width) + "_s" + std::to_string(seed) + ".exr";
    EXPECT_EQ(run({"render", scene, "-q", "--no-png", "--seed", std::to_string(seed), "-o", exr}), 0);
    return exr;
  }
  std::string dir;
};

TEST_F(MetricsCli, PrintsTheLibraryMetricsAndAnErrorMap) {
  const std::string a = renderTiny(12, 1), b = renderTiny(12, 2), map = dir + "/err.pfm";
  std::string out, err;
  ASSERT_EQ(run({"metrics", a, b, "--error-map", map}, &out, &err), 0) << err;
  const json j = json::parse(out);
  const ImageError expected = compareImages(readExrXyz(a), readExrXyz(b));
  ASSERT_GT(expected.rmse, 0.0) << "two seeds gave the same image: the test has no power";
  EXPECT_NEAR(j.at("rmse").get<double>(), expected.rmse, 1e-12 * expected.rmse);
  EXPECT_NEAR(j.at("relmse").get<double>(), expected.relMse, 1e-12 * expected.relMse);
  EXPECT_EQ(j.at("width"), 12);
  EXPECT_EQ(j.at("height"), 8);

  // The PFM: header, then bottom-to-top float rows whose mean is the relMSE.
  const std::string pfm = test::readTextFile(map);
  const std::string header = "Pf\n12 8\n-1.0\n";
  ASSERT_EQ(pfm.size(), header.size() + 12 * 8 * sizeof(float));
  EXPECT_EQ(pfm.substr(0, header.size()), header);
  std::vector<float> values(12 * 8);
  std::memcpy(values.data(), pfm.data() + header.size(), values.size() * sizeof(float));
  const std::vector<float> top = relativeErrorMap(readExrXyz(a), readExrXyz(b));
  for (int x = 0; x < 12; ++x) EXPECT_EQ(values[size_t(7) * 12 + x], top[x]) << "the first image row is last";
  double mean = 0.0;
  for (float v : values) mean += v / double(values.size());
  EXPECT_NEAR(mean, expected.relMse, 1e-6 * expected.relMse);

  ASSERT_EQ(run({"metrics", a, a}, &out), 0);
  EXPECT_EQ(json::parse(out).at("rmse").get<double>(), 0.0);
}

TEST_F(MetricsCli, BadInputNamesTheFile) {
  const std::string a = renderTiny(12, 1), other = renderTiny(10, 1), missing = dir + "/missing.exr";
  std::string err;
  EXPECT_EQ(run({"metrics", missing, a}, nullptr, &err), 1);
  EXPECT_EQ(err.rfind("kasha: error: " + missing, 0), 0u) << err;
  EXPECT_EQ(run({"metrics", other, a}, nullptr, &err), 1);
  EXPECT_EQ(err.rfind("kasha: error: " + other, 0), 0u) << err;
  EXPECT_NE(err.find("the reference is 12x8, the image 10x8"), std::string::npos) << err;
  EXPECT_EQ(run({"metrics", a}, nullptr, &err), 2) << "a missing argument is a command-line error";
}

}  // namespace
}  // namespace kasha
