// Spectral bins and the emissive spectral OpenEXR layout of Fichet, Pacanowski & Wilkie (2021):
// channel names and attributes as the layout defines them, bit-exact read-back, other writers'
// wavelength spellings, integration to XYZ, checkpoints with spectral sums, and the CLI
// (--spectral-bins / --spectral-step, metrics against a spectral-only reference, resume).
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <ImfOutputFile.h>
#include <ImfStringAttribute.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>

#include <nlohmann/json.hpp>

#include "core/checkpoint.h"
#include "core/color.h"
#include "core/error.h"
#include "core/image_input.h"
#include "core/image_output.h"
#include "core/spectral_exr.h"
#include "core/spectral_film.h"
#include "integrators/comparison.h"
#include "tests/expect_contains.h"
#include "tests/process.h"

namespace kasha {
namespace {

namespace fs = std::filesystem;

class SpectralExr : public ::testing::Test {
 protected:
  void SetUp() override {
    dir = (fs::path(::testing::TempDir()) / ("kasha_spectral_exr." + std::to_string(getpid()))).string();
    fs::create_directories(dir);
  }
  void TearDown() override {
    if (!HasFailure()) fs::remove_all(dir);
  }
  std::string dir;
};

// A film and its spectral bins (10 nm over 360–830) with random samples.
struct Films {
  Film film{3, 2};
  SpectralFilm spectral{3, 2, SpectralBins::fromStep(WavelengthRange{}, 10.0f)};
  explicit Films(uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    for (int y = 0; y < 2; ++y)
      for (int x = 0; x < 3; ++x)
        for (int s = 0; s < 20; ++s) {
          const float lambda = 360.0f + 470.0f * u(rng), v = 3.0f * u(rng);
          film.add(x, y, Observer::cie1931().weight(lambda) * v);
          spectral.add(x, y, lambda, v);
        }
    film.setSamplesPerPixel(20);
    spectral.setSamplesPerPixel(20);
  }
};

// Writes an image `height` rows high with the given channels, each holding `values` (row-major).
void writeChannels(const std::string& path, const std::vector<std::string>& names, std::vector<float> values,
                   int height = 1) {
  const int w = int(values.size()) / height;
  Imf::Header header(w, height);
  Imf::FrameBuffer fb;
  for (const std::string& n : names) {
    header.channels().insert(n, Imf::Channel(Imf::FLOAT));
    fb.insert(n, Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(values.data()), sizeof(float), sizeof(float) * w));
  }
  Imf::OutputFile file(path.c_str(), header);
  file.setFrameBuffer(fb);
  file.writePixels(height);
}

TEST(SpectralBins, FromCountAndStep) {
  const SpectralBins b = SpectralBins::fromStep(WavelengthRange{}, 10.0f);
  EXPECT_EQ(b.count, 47);
  EXPECT_FLOAT_EQ(b.centre(0), 365.0f);
  EXPECT_EQ(b.index(360.0f), 0);
  EXPECT_EQ(b.index(369.999f), 0);
  EXPECT_EQ(b.index(370.0f), 1);
  EXPECT_EQ(b.index(830.0f), 46);  // the upper end belongs to the last bin
  EXPECT_EQ(b.index(359.9f), -1);
  EXPECT_EQ(b.index(830.1f), -1);
  EXPECT_EQ(SpectralBins::fromCount(WavelengthRange{300.0f, 800.0f}, 5).step, 100.0f);
  EXPECT_THROW(SpectralBins::fromStep(WavelengthRange{}, 7.0f), std::invalid_argument);  // 470 / 7
  EXPECT_THROW(SpectralBins::fromCount(WavelengthRange{}, 0), std::invalid_argument);
  EXPECT_THROW(SpectralBins::fromCount(WavelengthRange{}, SpectralBins::kMaxBins + 1), std::invalid_argument);
}

// The estimator: a sample's value v at λ adds v/Δ to λ's bin; the film divides by spp.
TEST(SpectralFilm, AveragesPerNanometre) {
  SpectralFilm f(1, 1, SpectralBins::fromCount(WavelengthRange{400.0f, 500.0f}, 2));
  f.add(0, 0, 420.0f, 5.0f);
  f.add(0, 0, 470.0f, 2.0f);
  f.add(0, 0, 399.0f, 100.0f);  // outside: dropped
  f.add(0, 0, 430.0f, std::numeric_limits<float>::infinity());  // non-finite: dropped
  f.setSamplesPerPixel(2);
  EXPECT_FLOAT_EQ(f.value(0, 0, 0), 5.0f / (2 * 50));
  EXPECT_FLOAT_EQ(f.value(0, 0, 1), 2.0f / (2 * 50));
}

TEST_F(SpectralExr, ChannelNamesAndAttributesFollowTheLayout) {
  const Films f(1);
  const std::string path = dir + "/a.exr";
  writeExr(f.film, path, &f.spectral);
  Imf::InputFile file(path.c_str());
  const Imf::Header& h = file.header();
  for (const char* c : {"R", "G", "B", "XYZ.X", "XYZ.Y", "XYZ.Z", "S0.365,000000nm", "S0.825,000000nm", "S0.595,000000nm"})
    EXPECT_NE(h.channels().findChannel(c), nullptr) << c;
  int emissive = 0;
  for (auto it = h.channels().begin(); it != h.channels().end(); ++it)
    if (std::strncmp(it.name(), "S0.", 3) == 0) ++emissive;
  EXPECT_EQ(emissive, 47);
  const auto* version = h.findTypedAttribute<Imf::StringAttribute>("spectralLayoutVersion");
  const auto* units = h.findTypedAttribute<Imf::StringAttribute>("emissiveUnits");
  ASSERT_NE(version, nullptr);
  ASSERT_NE(units, nullptr);
  EXPECT_EQ(version->value(), "1.0");
  EXPECT_EQ(units->value(), "W.m^-2.sr^-1");
}

TEST_F(SpectralExr, ReadsBackBitExactly) {
  const Films f(2);
  const std::string path = dir + "/b.exr";
  writeExr(f.film, path, &f.spectral);
  const SpectralImage img = readSpectralExr(path);
  ASSERT_EQ(img.width, 3);
  ASSERT_EQ(img.height, 2);
  ASSERT_EQ(img.wavelengths.size(), 47u);
  bool nonZero = false;
  for (int y = 0; y < 2; ++y)
    for (int x = 0; x < 3; ++x)
      for (int b = 0; b < 47; ++b) {
        EXPECT_EQ(img.wavelengths[size_t(b)], f.spectral.bins().centre(b));
        const float expected = f.spectral.value(x, y, b), got = img.at(x, y, size_t(b));
        EXPECT_EQ(std::memcmp(&expected, &got, sizeof got), 0) << x << " " << y << " " << b;
        nonZero |= got != 0.0f;
      }
  EXPECT_TRUE(nonZero);
}

// Other writers (pbrt-v4, Mitsuba 3, ART) spell wavelengths in other units; a constant radiance
// of 1 per nm over 360–830 nm integrates to Y = 1 in the film's normalisation (core/color.h).
TEST_F(SpectralExr, OtherSpellingsIntegrateToXyz) {
  std::vector<std::string> names;
  for (int l = 360; l <= 830; l += 5)
    names.push_back(l % 2 ? "S0." + std::to_string(l) + "nm" : "S0.0," + std::to_string(l) + "um");
  const std::string path = dir + "/c.exr";
  writeChannels(path, names, {1.0f, 2.0f});
  const SpectralImage img = readSpectralExr(path);
  ASSERT_EQ(img.wavelengths.size(), 95u);
  EXPECT_FLOAT_EQ(img.wavelengths[1], 365.0f);
  const XyzImage xyz = readExrXyz(path);  // no XYZ layer: integrated from the bins
  ASSERT_EQ(xyz.pixels.size(), 2u);
  // The end bands reach 2.5 nm past 360 and 830, where the observer's table is zero.
  EXPECT_NEAR(xyz.pixels[0].y, 1.0f, 1e-4f);
  EXPECT_NEAR(xyz.pixels[1].y, 2.0f, 2e-4f);
  const Observer& o = Observer::cie1931();
  EXPECT_NEAR(xyz.pixels[0].x, o.xbar.integral(360.0f, 830.0f) / o.yIntegral, 1e-4f);
  EXPECT_NEAR(xyz.pixels[0].z, o.zbar.integral(360.0f, 830.0f) / o.yIntegral, 1e-4f);
}

TEST_F(SpectralExr, BadFilesNameTheFileAndChannel) {
  const std::string twice = dir + "/twice.exr", none = dir + "/none.exr";
  writeChannels(twice, {"S0.500nm", "S0.0,5um"}, {1.0f});
  try {
    readSpectralExr(twice);
    FAIL() << "a wavelength given twice was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("twice.exr: S0."), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("same wavelength"), std::string::npos) << e.what();
  }
  writeChannels(none, {"Y"}, {1.0f});
  try {
    readExrXyz(none);
    FAIL() << "a file without XYZ or S0 channels was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("none.exr"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("S0."), std::string::npos) << e.what();
  }
}

// Issue 15's rules for every file read: regular files only (a FIFO neither blocks nor is read),
// the decoded channels counted against the memory limit before decoding, non-finite values refused.
TEST_F(SpectralExr, ReaderFollowsTheFileRules) {
  const auto message = [](const auto& read) -> std::string {
    try {
      read();
    } catch (const InputError& e) {
      return e.what();
    }
    return "(no error)";
  };
  const std::string fifo = dir + "/fifo.exr";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  EXPECT_CONTAINS(message([&] { readSpectralExr(fifo); }), "fifo.exr: cannot open image file");
  EXPECT_CONTAINS(message([&] { readExrXyz(fifo); }), "not a regular file");

  const std::string big = dir + "/big.exr";  // 100 channels of 4x4 pixels: 16·(400 + 12) bytes
  std::vector<std::string> names;
  for (int l = 400; l < 500; ++l) names.push_back(emissiveChannelName(float(l)));
  writeChannels(big, names, std::vector<float>(16, 1.0f), 4);
  EXPECT_EQ(readSpectralExr(big, 16 * 412).wavelengths.size(), 100u);
  EXPECT_CONTAINS(message([&] { readSpectralExr(big, 16 * 412 - 1); }), "big.exr: ");
  EXPECT_CONTAINS(message([&] { readExrXyz(big, 16 * 412 - 1); }), "memory limit");

  const std::string nan = dir + "/nan.exr";
  writeChannels(nan, {"S0.500nm"}, {1.0f, std::nanf(""), 1.0f, 1.0f}, 2);
  EXPECT_EQ(message([&] { readExrXyz(nan); }), nan + ": S0.500nm: pixel (1, 0) is not finite");
  // Finite radiance whose integral is not: z̄ integrates to a little more than ȳ (the normalisation).
  const std::string huge = dir + "/huge.exr";
  writeChannels(huge, {"S0.360nm", "S0.830nm"}, {std::numeric_limits<float>::max()});
  EXPECT_EQ(message([&] { readExrXyz(huge); }), huge + ": pixel (0, 0) integrates to a non-finite XYZ");
}

TEST_F(SpectralExr, CheckpointKeepsTheSpectralSums) {
  const Films f(3);
  const std::string path = dir + "/c.ckpt";
  writeCheckpoint(path, {{"k", 1}}, {{"r", 2}}, f.film, &f.spectral);
  Film film(3, 2);
  SpectralFilm spectral(3, 2, f.spectral.bins());
  restoreFilm(readCheckpoint(path), film, &spectral);
  ASSERT_EQ(spectral.sums().size(), f.spectral.sums().size());
  EXPECT_EQ(std::memcmp(spectral.sums().data(), f.spectral.sums().data(), spectral.sums().size() * sizeof(double)), 0);
  EXPECT_EQ(spectral.samplesPerPixel(), 20);
  Film plain(3, 2);
  EXPECT_THROW(restoreFilm(readCheckpoint(path), plain), InputError);  // the render has no bins
  SpectralFilm other(3, 2, SpectralBins::fromCount(WavelengthRange{}, 10));
  EXPECT_THROW(restoreFilm(readCheckpoint(path), plain, &other), InputError);
  // Truncating the spectral block is detected.
  fs::resize_file(path, fs::file_size(path) - 16);
  EXPECT_THROW(readCheckpoint(path), InputError);
}

// The command line: bins in the EXR, refusals, metrics against a spectral-only reference, and a
// resumed render whose bins are bit-identical to an uninterrupted one (path tracing: no splats).
TEST_F(SpectralExr, CommandLine) {
  const std::string scene = std::string(KASHA_SOURCE_DIR) + "/scenes/validation/furnace_fluorescent.json";
  const std::string whole = dir + "/whole.exr", part = dir + "/part.exr", ckpt = dir + "/r.ckpt";
  test::Finished r = test::runKasha({"render", scene, "-q", "--no-png", "--spp", "16", "--spectral-step", "10", "-o", whole},
                                    dir + "/w");
  ASSERT_EQ(r.code, 0) << r.err;
  r = test::runKasha({"render", scene, "-q", "--no-png", "--spp", "8", "--spectral-step", "10", "--checkpoint", ckpt,
                      "-o", part}, dir + "/p1");
  ASSERT_EQ(r.code, 0) << r.err;
  r = test::runKasha({"render", scene, "-q", "--no-png", "--spp", "16", "--spectral-step", "10", "--resume", ckpt, "-o",
                      part}, dir + "/p2");
  ASSERT_EQ(r.code, 0) << r.err;
  const SpectralImage a = readSpectralExr(whole), b = readSpectralExr(part);
  ASSERT_EQ(a.values.size(), 8u * 8u * 47u);
  EXPECT_EQ(std::memcmp(a.values.data(), b.values.data(), a.values.size() * sizeof(float)), 0);
  r = test::runKasha({"render", scene, "-q", "--no-png", "--spp", "16", "--spectral-bins", "4", "--resume", ckpt, "-o",
                      part}, dir + "/p3");
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("spectral_bins"), std::string::npos) << r.err;

  r = test::runKasha({"render", scene, "-q", "--no-png", "--spectral-step", "7", "-o", part}, dir + "/e1");
  EXPECT_EQ(r.code, 2);  // a command-line mistake
  EXPECT_NE(r.err.find("--spectral-step: spectral step: 7 nm does not divide"), std::string::npos) << r.err;
  // pt keeps bins with its wavelength lanes (each lane's share per sensor wavelength).
  r = test::runKasha({"render", scene, "-q", "--no-png", "--hero", "4", "--spectral-bins", "4", "-o", part}, dir + "/e2");
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(nlohmann::json::parse(test::readTextFile(dir + "/part.stats.json")).at("hero_wavelengths"), 4);
  r = test::runKasha({"render", scene, "-q", "--no-png", "--spectral-bins", "100", "--memory-limit", "16K", "-o", part},
                     dir + "/e3");
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("100 spectral bins"), std::string::npos) << r.err;

  // A reference with only S0 channels (as pbrt-v4 writes): metrics integrates it to XYZ.
  const std::string ref = dir + "/ref.exr";
  std::vector<std::string> names;
  for (const float l : a.wavelengths) names.push_back(emissiveChannelName(l));
  std::vector<float> values(64);
  for (size_t i = 0; i < values.size(); ++i) values[i] = 1.0f + 0.05f * float(i);
  writeChannels(ref, names, values, 8);
  r = test::runKasha({"metrics", whole, ref}, dir + "/m1");
  ASSERT_EQ(r.code, 0) << r.err;
  const ImageError expected = compareImages(readExrXyz(whole), spectralToXyz(readSpectralExr(ref)));
  EXPECT_GT(expected.rmse, 0.1);
  EXPECT_NEAR(nlohmann::json::parse(r.out).at("rmse").get<double>(), expected.rmse, 1e-9 * expected.rmse);
}

}  // namespace
}  // namespace kasha
