// Memory limits (core/memory_budget.h): sizes with suffixes, the check itself, and its uses — a
// mesh too large for the limit is refused before it is read, a film too large before it is
// allocated, a reradiation matrix too large before it is computed — each with a clear error and
// exit code 1, not an out-of-memory kill.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include <nlohmann/json.hpp>

#include "core/error.h"
#include "core/film.h"
#include "core/memory_budget.h"
#include "scene/scene_loader.h"
#include "tests/process.h"
#include "tests/expect_contains.h"

namespace kasha {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

TEST(MemoryBudget, ParsesSizes) {
  EXPECT_EQ(parseByteSize("65536"), 65536u);
  EXPECT_EQ(parseByteSize("100B"), 100u);
  EXPECT_EQ(parseByteSize("1k"), 1024u);
  EXPECT_EQ(parseByteSize("64KiB"), 64u << 10);
  EXPECT_EQ(parseByteSize("512M"), 512u << 20);
  EXPECT_EQ(parseByteSize("8G"), uint64_t(8) << 30);
  EXPECT_EQ(parseByteSize("1.5g"), uint64_t(3) << 29);
  EXPECT_EQ(parseByteSize("2TB"), uint64_t(2) << 40);
  for (const char* bad : {"", "G", "12Q", "-1", "1e3", "0", "0.1", "1.2.3", "8 G", "8GG", "16777216T"}) {
    SCOPED_TRACE(bad);
    EXPECT_THROW(parseByteSize(bad), std::invalid_argument);
  }
}

TEST(MemoryBudget, FormatsSizes) {
  EXPECT_EQ(formatBytes(1), "1 byte");
  EXPECT_EQ(formatBytes(100), "100 bytes");
  EXPECT_EQ(formatBytes(1536), "1.50 KiB");
  EXPECT_EQ(formatBytes(uint64_t(8) << 30), "8.00 GiB");
  EXPECT_EQ(formatBytes(uint64_t(300) << 20), "300 MiB");
}

TEST(MemoryBudget, RequireMemory) {
  EXPECT_NO_THROW(requireMemory(1024, "x", 1024));
  try {
    requireMemory(2048, "the photon map (10 photons)", 1024);
    ADD_FAILURE() << "expected a MemoryLimitError";
  } catch (const MemoryLimitError& e) {
    EXPECT_EQ(std::string(e.what()),
              "the photon map (10 photons) needs 2.00 KiB, more than the memory limit of 1.00 KiB (raise it with "
              "--memory-limit)");
  }
  EXPECT_EQ(saturatingMul(uint64_t(1) << 40, uint64_t(1) << 40), UINT64_MAX);
  EXPECT_EQ(saturatingMul(0, UINT64_MAX), 0u);
  EXPECT_THROW(requireMemory(saturatingMul(UINT64_MAX, 2), "x", kDefaultMemoryLimit), MemoryLimitError);
  EXPECT_EQ(Film::bytesFor(1920, 1080), uint64_t(1920) * 1080 * 48);
}

class MemoryLimits : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir = (fs::path(::testing::TempDir()) / ("kasha_memory." + std::to_string(getpid())) / info->name()).string();
    fs::remove_all(dir);
    fs::create_directories(dir);
  }
  void TearDown() override {
    if (!HasFailure()) fs::remove_all(fs::path(dir).parent_path());
  }
  std::string write(const std::string& name, const std::string& text) const {
    std::ofstream(dir + "/" + name, std::ios::binary) << text;
    return dir + "/" + name;
  }
  std::string dir;
};

const char* kScene = R"({
  "camera": {"position": [0, 0, -3], "look_at": [0, 0, 0], "fov": 40, "resolution": [64, 32]},
  "materials": {"white": {"type": "lambertian", "reflectance": 0.5},
                "dye": {"type": "jung_fluorescent", "absorption": {"type": "gaussian", "center": 450, "fwhm": 40},
                        "emission": {"type": "gaussian", "center": 520, "fwhm": 30}, "reflectance": 0.5, "c": 0.5, "Q": 0.9}},
  "shapes": [{"type": "rectangle", "center": [0, 0, 0], "u": [1, 0, 0], "v": [0, 1, 0],
              "material": "white", "emission": {"radiance": 1}},
             {"type": "mesh", "file": "grid.obj", "material": "white"}]
})";

// An OBJ of about 20 KiB: a strip of 300 triangles.
std::string gridObj() {
  std::string s;
  for (int i = 0; i <= 150; ++i) s += "v " + std::to_string(i) + ".000000 0.000000 0.000000\nv " + std::to_string(i) + ".000000 1.000000 0.000000\n";
  for (int i = 0; i < 150; ++i) {
    const int a = 2 * i + 1;
    s += "f " + std::to_string(a) + " " + std::to_string(a + 2) + " " + std::to_string(a + 1) + "\n";
    s += "f " + std::to_string(a + 1) + " " + std::to_string(a + 2) + " " + std::to_string(a + 3) + "\n";
  }
  return s;
}

TEST_F(MemoryLimits, MeshLargerThanTheLimitIsRefusedBeforeReading) {
  const std::string obj = write("grid.obj", gridObj());
  const std::string scene = write("scene.json", kScene);
  SceneLoadOptions options;
  EXPECT_EQ(loadScene(scene, options)->shapes[1].indices.size(), 900u);
  options.memoryLimit = 64 << 10;  // the mesh needs about 6 × its size
  try {
    loadScene(scene, options);
    ADD_FAILURE() << "expected an InputError";
  } catch (const InputError& e) {
    const std::string msg = e.what();
    EXPECT_EQ(msg.rfind(scene + ": /shapes/1/file: '" + obj + "' (", 0), 0u) << msg;
    EXPECT_CONTAINS(msg, "KiB): reading it needs ");
    EXPECT_CONTAINS(msg, "more than the memory limit of 64.0 KiB (raise it with --memory-limit)");
  }
}

TEST_F(MemoryLimits, CliRefusesAFilmOrMatrixOverTheLimit) {
  write("grid.obj", gridObj());
  const std::string scene = write("scene.json", kScene);
  // 64×32 pixels: 96 KiB of sums plus 48 KiB of EXR channels.
  auto r = test::runKasha({"render", scene, "-q", "--spp", "1", "--memory-limit", "140K", "-o", dir + "/a.exr"},
                          dir + "/a");
  EXPECT_EQ(r.code, 1);
  EXPECT_EQ(r.err, "kasha: error: the film (64x32 pixels) needs 144 KiB, more than the memory limit of 140 KiB (raise it "
                   "with --memory-limit)\n");
  EXPECT_FALSE(fs::exists(dir + "/a.exr"));
  r = test::runKasha({"render", scene, "-q", "--spp", "1", "--memory-limit", "1M", "-o", dir + "/a.exr"}, dir + "/a");
  EXPECT_EQ(r.code, 0) << r.err;
  // A reradiation matrix on a 0.0001 nm grid would need terabytes.
  r = test::runKasha({"matrix", scene, "--material", "dye", "--step", "0.0001"}, dir + "/m");
  EXPECT_EQ(r.code, 1);
  EXPECT_CONTAINS(r.err, "kasha: error: a 47000");
  EXPECT_CONTAINS(r.err, " matrix (--step 0.000100) needs ");
  EXPECT_CONTAINS(r.err, "more than the memory limit of 8.00 GiB");
  EXPECT_TRUE(r.out.empty());
}

}  // namespace
}  // namespace kasha
