// Mitsuba's .vol grids (core/volume_grid.h): files written field by field here are read back cell
// by cell, trilinear lookups reproduce multilinear functions of the cell centres exactly (and clamp
// beyond them), the maximum bounds every lookup, and every lie in a header is a one-line
// InputError naming the file, found before the data is allocated.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "core/error.h"
#include "core/memory_budget.h"
#include "core/volume_grid.h"
#include "tests/temp_dir.h"
#include "tests/volume_grid_files.h"

namespace kasha {
namespace {

using test::volBytes;

constexpr uint64_t kLimit = uint64_t(1) << 30;

// Cell (x, y, z) of an nx × ny × nz grid holds f at its centre ((i + 1/2)/n per axis).
template <class F>
std::vector<float> sampledAtCentres(int nx, int ny, int nz, F f) {
  std::vector<float> v;
  for (int z = 0; z < nz; ++z)
    for (int y = 0; y < ny; ++y)
      for (int x = 0; x < nx; ++x) v.push_back(f((x + 0.5f) / nx, (y + 0.5f) / ny, (z + 0.5f) / nz));
  return v;
}

// The message of the error parsing `bytes` throws ("" and a failure if none).
std::string parseError(const std::string& bytes, uint64_t limit = kLimit) {
  try {
    VolumeGrid::parse(bytes, "grid.vol", limit);
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  ADD_FAILURE() << "parsed, expected an error";
  return "";
}

TEST(VolumeGrid, CellsAreInMitsubasOrder) {
  // data[((z·ny + y)·nx + x)·channels + c] (Mitsuba 3 docs: gridvolume).
  std::vector<float> values;
  for (int i = 0; i < 2 * 3 * 4 * 3; ++i) values.push_back(float(i));
  const VolumeGrid g = VolumeGrid::parse(volBytes({2, 3, 4}, 3, values, {-1, -2, -3, 1, 2, 3}), "grid.vol", kLimit);
  EXPECT_EQ(g.resolution(), (std::array<int, 3>{2, 3, 4}));
  EXPECT_EQ(g.channels(), 3);
  EXPECT_EQ(g.boxMin(), Vec3(-1, -2, -3));
  EXPECT_EQ(g.boxMax(), Vec3(1, 2, 3));
  EXPECT_EQ(g.cell(1, 0, 0, 0), 3.0f);
  EXPECT_EQ(g.cell(0, 1, 0, 0), 6.0f);
  EXPECT_EQ(g.cell(0, 0, 1, 2), 20.0f);
  EXPECT_EQ(g.cell(1, 2, 3, 1), float(((3 * 3 + 2) * 2 + 1) * 3 + 1));
  EXPECT_EQ(g.maximum(0), 69.0f);
  EXPECT_EQ(g.maximum(2), 71.0f);
}

TEST(VolumeGrid, TrilinearLookupReproducesMultilinearFunctions) {
  // Trilinear interpolation is exact for a + b·x + c·y + d·z + e·x·y·z between the cell centres.
  const auto f = [](float x, float y, float z) { return 1.0f + 2.0f * x + 3.0f * y + 0.5f * z + 4.0f * x * y * z; };
  const int nx = 4, ny = 3, nz = 5;
  const VolumeGrid g = VolumeGrid::parse(volBytes({nx, ny, nz}, 1, sampledAtCentres(nx, ny, nz, f)), "grid.vol", kLimit);
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  const auto inside = [&](int n) { return (0.5f + u(rng) * float(n - 1)) / float(n); };  // between the outermost centres
  for (int k = 0; k < 200; ++k) {
    const Vec3 p(inside(nx), inside(ny), inside(nz));
    EXPECT_NEAR(g.lookup(p), f(p.x, p.y, p.z), 1e-5f) << p.x << " " << p.y << " " << p.z;
  }
  // Beyond the outermost centres, and outside the unit cube, coordinates clamp to them.
  EXPECT_NEAR(g.lookup(Vec3(0.01f, 0.5f, 0.5f)), f(0.5f / nx, 0.5f, 0.5f), 1e-5f);
  EXPECT_NEAR(g.lookup(Vec3(-3.0f, 7.0f, 0.5f)), f(0.5f / nx, 1.0f - 0.5f / ny, 0.5f), 1e-5f);
  EXPECT_EQ(g.lookup(Vec3(std::numeric_limits<float>::quiet_NaN(), 0.0f, 0.0f)), g.cell(0, 0, 0));
  // The stored box maps onto the unit cube.
  const VolumeGrid boxed = VolumeGrid::parse(volBytes({nx, ny, nz}, 1, sampledAtCentres(nx, ny, nz, f), {-2, 0, 10, 2, 1, 20}),
                                             "grid.vol", kLimit);
  EXPECT_NEAR(boxed.lookupInBox(Vec3(0.0f, 0.5f, 15.0f)), f(0.5f, 0.5f, 0.5f), 1e-5f);
}

// The wrap modes (Mitsuba 3 docs: gridvolume, wrap_mode) on a row of 4 cells 1, 2, 4, 8 whose
// centres sit at x = (i + 1/2)/4; values worked out by hand from the cells' neighbours.
TEST(VolumeGrid, WrapModesFindTheStencilsCells) {
  const VolumeGrid g = VolumeGrid::parse(volBytes({4, 1, 1}, 1, {1, 2, 4, 8}), "grid.vol", kLimit);
  const auto at = [&](float x, GridWrap wrap) { return g.lookup(Vec3(x, 0.3f, -7.0f), 0, wrap); };
  // Inside the outermost centres every mode interpolates: x = 0.3 is 0.7 of the way from cell 0 to 1.
  for (GridWrap w : {GridWrap::Clamp, GridWrap::Repeat, GridWrap::Mirror}) EXPECT_NEAR(at(0.3f, w), 1.7f, 1e-5f);
  // Repeat: the last cell's neighbour is the first (x = 0 and x = 1 halfway between 8 and 1), and
  // x ≡ x + 1: 1.3 is 0.3, −0.2 is 0.8 (0.7 of the way from 4 to 8), 1000.3 is 0.3.
  EXPECT_NEAR(at(0.0f, GridWrap::Repeat), 4.5f, 1e-5f);
  EXPECT_NEAR(at(1.0f, GridWrap::Repeat), 4.5f, 1e-5f);
  EXPECT_NEAR(at(1.3f, GridWrap::Repeat), 1.7f, 1e-5f);
  EXPECT_NEAR(at(-0.2f, GridWrap::Repeat), 6.8f, 1e-5f);
  EXPECT_NEAR(at(1000.3f, GridWrap::Repeat), 1.7f, 1e-3f);
  EXPECT_NEAR(at(-3.2f, GridWrap::Repeat), 6.8f, 1e-4f);
  // Mirror: reflected at each face, so 1.3 reads 0.7 (0.3 of the way from 4 to 8), 1.1 the last
  // cell, −0.1 the first, 2.3 (reflected twice) 0.3.
  EXPECT_NEAR(at(1.3f, GridWrap::Mirror), 5.2f, 1e-5f);
  EXPECT_NEAR(at(1.1f, GridWrap::Mirror), 8.0f, 1e-5f);
  EXPECT_NEAR(at(-0.1f, GridWrap::Mirror), 1.0f, 1e-5f);
  EXPECT_NEAR(at(2.3f, GridWrap::Mirror), 1.7f, 1e-4f);
  // Clamp: the edge cells beyond the outermost centres.
  EXPECT_NEAR(at(1.3f, GridWrap::Clamp), 8.0f, 1e-5f);
  EXPECT_NEAR(at(-0.2f, GridWrap::Clamp), 1.0f, 1e-5f);
  // A NaN coordinate reads the first cell in every mode; an infinite one too where the grid repeats.
  const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
  for (GridWrap w : {GridWrap::Clamp, GridWrap::Repeat, GridWrap::Mirror}) EXPECT_EQ(at(nan, w), 1.0f);
  EXPECT_EQ(at(inf, GridWrap::Repeat), 1.0f);
  EXPECT_EQ(at(inf, GridWrap::Clamp), 8.0f);
  EXPECT_EQ(gridWrapNamed("repeat"), GridWrap::Repeat);
  EXPECT_EQ(gridWrapNamed("mirror"), GridWrap::Mirror);
  EXPECT_EQ(gridWrapNamed("clamp"), GridWrap::Clamp);
  EXPECT_FALSE(gridWrapNamed("zero"));
}

TEST(VolumeGrid, MaximumBoundsEveryLookup) {
  std::mt19937 rng(7);
  std::exponential_distribution<float> density(1.0f);
  std::vector<float> values(6 * 6 * 6);
  for (float& v : values) v = density(rng);
  const VolumeGrid g = VolumeGrid::parse(volBytes({6, 6, 6}, 1, values), "grid.vol", kLimit);
  EXPECT_EQ(g.maximum(), *std::max_element(values.begin(), values.end()));
  std::uniform_real_distribution<float> u(-0.1f, 1.1f);
  float largest = 0.0f;
  for (int k = 0; k < 2000; ++k) largest = std::max(largest, g.lookup(Vec3(u(rng), u(rng), u(rng))));
  EXPECT_LE(largest, g.maximum());
  EXPECT_GT(largest, 0.5f * g.maximum());
}

TEST(VolumeGrid, HeadersThatLieAreOneLineErrors) {
  const std::vector<float> eight(8, 1.0f);
  const std::string good = volBytes({2, 2, 2}, 1, eight);
  const auto expectError = [](const std::string& message, const std::string& part) {
    EXPECT_NE(message.find(part), std::string::npos) << message;
    EXPECT_EQ(message.rfind("grid.vol: ", 0), 0u) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  };
  expectError(parseError(good.substr(0, 47)), "header: the file is 47 bytes, shorter than the 48-byte header");
  expectError(parseError("VOX" + good.substr(3)), "header: not a Mitsuba volume grid");
  expectError(parseError(volBytes({2, 2, 2}, 1, eight, {0, 0, 0, 1, 1, 1}, 2)), "header: unknown version 2");
  expectError(parseError(volBytes({2, 2, 2}, 1, eight, {0, 0, 0, 1, 1, 1}, 3, 2)), "header: encoding 2 is not read");
  expectError(parseError(volBytes({2, 0, 2}, 1, {})), "header: cells along y must be at least 1, got 0");
  expectError(parseError(volBytes({2, 2, -4}, 1, eight)), "header: cells along z must be at least 1, got -4");
  expectError(parseError(volBytes({2, 2, 2}, 2, eight)), "header: channels must be 1, 3 or 6, got 2");
  expectError(parseError(volBytes({2, 2, 2}, 1, eight, {0, 0, 1, 1, 1, 1})), "header: the bounding box along z");
  expectError(parseError(volBytes({2, 2, 2}, 1, eight, {0, std::nanf(""), 0, 1, 1, 1})), "header: the bounding box along y");
  expectError(parseError(good.substr(0, good.size() - 4)), "declares 2x2x2 cells of 1 channels (32 bytes), but 28 bytes follow");
  expectError(parseError(good + "x"), "but 33 bytes follow the header");
  // Counts whose product overflows 64 bits, or would need terabytes, are refused by the file's size.
  expectError(parseError(volBytes({2147483647, 2147483647, 2147483647}, 6, eight)), "(more than 2^64 bytes), but 32 bytes follow");
  expectError(parseError(volBytes({65536, 65536, 1024}, 1, eight)), "declares 65536x65536x1024 cells of 1 channels (17592186044416 bytes)");
  // Data that is there but exceeds the memory limit: refused before it is copied.
  expectError(parseError(good, 16), "the volume grid (2x2x2 cells of 1 channels) needs");
  // Values: finite, not negative.
  expectError(parseError(volBytes({2, 2, 2}, 1, {1, 1, 1, 1, 1, std::nanf(""), 1, 1})), "data: value 5 (channel 0) is nan");
  expectError(parseError(volBytes({2, 1, 1}, 3, {1, 1, 1, 1, -2, 1})), "data: value 1 (channel 1) is -2");
}

class VolumeGridFile : public test::TempDirTest {
 protected:
  VolumeGridFile() : TempDirTest("volume_grid") {}
};

TEST_F(VolumeGridFile, ReadsWhatParseReads) {
  const std::vector<float> values = sampledAtCentres(3, 2, 2, [](float x, float y, float z) { return x + 10 * y + 100 * z; });
  const VolumeGrid g = VolumeGrid::read(writeFile("a.vol", volBytes({3, 2, 2}, 1, values)), kLimit);
  for (int z = 0; z < 2; ++z)
    for (int y = 0; y < 2; ++y)
      for (int x = 0; x < 3; ++x) EXPECT_EQ(g.cell(x, y, z), values[size_t((z * 2 + y) * 3 + x)]);
  // A header declaring 16 GiB in a 56-byte file: an error from the header alone.
  const std::string lying = writeFile("lying.vol", volBytes({2048, 2048, 1024}, 1, {1, 2}));
  try {
    VolumeGrid::read(lying, kLimit);
    ADD_FAILURE() << "read a lying header";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(lying + ": header: declares 2048x2048x1024 cells"), std::string::npos) << e.what();
  }
  EXPECT_THROW(VolumeGrid::read(writeFile("short.vol", "VOL"), kLimit), InputError);
  EXPECT_THROW(VolumeGrid::read(dir + "/missing.vol", kLimit), InputError);
  EXPECT_THROW(VolumeGrid::read(writeFile("big.vol", volBytes({3, 2, 2}, 1, values)), 16), MemoryLimitError);
}

}  // namespace
}  // namespace kasha
