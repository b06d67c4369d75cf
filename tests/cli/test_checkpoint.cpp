// Interrupted renders lose nothing. The kasha binary, run as a child process:
// - a checkpointing render killed with SIGKILL and resumed gives the image of an uninterrupted
//   render with the same seed, bit for bit (the film's double sums and the EXR's floats), for the
//   path tracer (camera samples only) and the light tracer (splats);
// - SIGINT and SIGTERM stop a render after the current pass: the image, PNG, statistics
//   ("interrupted": true) and checkpoint are written, and the exit code is 130 or 143;
// - a checkpoint that does not match the render (any setting of the estimator), or is truncated,
//   corrupted or forged (a deeply nested or out-of-range header, with or without the right
//   checksum), is refused with one line naming it.
//
// Why bit-identical and not merely close: sample s of pixel p draws from the PCG32 stream
// (seed, p, s) whatever the pass or thread; a pixel's camera samples are added to its double sum in
// sample order; splats are merged after each pass in tile order, and the resumed render groups
// samples into the same passes (the checkpoint stores the samples per pass and is written only at
// pass boundaries). So the resumed render performs the same floating-point additions in the same
// order as the uninterrupted one, and the checkpoint stores the sums' exact bits.
#include <gtest/gtest.h>

#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <ImfChannelList.h>

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>

#include <nlohmann/json.hpp>

#include "core/checkpoint.h"
#include "tests/process.h"
#include "tests/expect_contains.h"

namespace kasha {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using test::runKasha;

// 32×32 pixels: 64 samples per pixel in a pass (at least 65536 samples per pass), so `kSpp` makes
// kSpp / 64 passes. A fluorescent sphere on a floor under an area light: camera paths and light
// paths (splats) both contribute.
constexpr int kSpp = 64 * 15;
const char* kScene = R"({
  "render": {"spp": 960, "max_depth": 6},
  "camera": {"position": [0, 1, -4], "look_at": [0, 1, 0], "fov": 50, "resolution": [32, 32]},
  "materials": {"white": {"type": "lambertian", "reflectance": 0.7},
                "dye": {"type": "jung_fluorescent",
                        "absorption": {"type": "gaussian", "center": 450, "fwhm": 40, "peak": 0.9},
                        "emission": {"type": "gaussian", "center": 520, "fwhm": 30},
                        "reflectance": 0.4, "c": 0.8, "Q": 0.9}},
  "shapes": [
    {"name": "floor", "type": "rectangle", "center": [0, 0, 0], "u": [0, 0, 2], "v": [2, 0, 0], "material": "white"},
    {"name": "ball", "type": "sphere", "center": [0, 1, 0], "radius": 0.7, "material": "dye"},
    {"name": "lamp", "type": "rectangle", "center": [0, 2.5, 0], "u": [0.5, 0, 0], "v": [0, 0, 0.5], "material": "white",
     "emission": {"radiance": "D65", "scale": 0.05, "two_sided": true}}
  ]
})";

// The channels of an EXR as written by kasha, by name.
std::map<std::string, std::vector<float>> readExr(const std::string& path) {
  Imf::InputFile file(path.c_str());
  const Imath::Box2i dw = file.header().dataWindow();
  const int w = dw.max.x - dw.min.x + 1, h = dw.max.y - dw.min.y + 1;
  std::map<std::string, std::vector<float>> channels;
  Imf::FrameBuffer fb;
  for (auto it = file.header().channels().begin(); it != file.header().channels().end(); ++it) {
    std::vector<float>& c = channels[it.name()];
    c.resize(size_t(w) * h);
    fb.insert(it.name(), Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(c.data() - dw.min.x - size_t(dw.min.y) * w),
                                    sizeof(float), sizeof(float) * w));
  }
  file.setFrameBuffer(fb);
  file.readPixels(dw.min.y, dw.max.y);
  return channels;
}

// Number of values whose bits differ.
size_t differingBits(const std::vector<float>& a, const std::vector<float>& b) {
  if (a.size() != b.size()) return std::max(a.size(), b.size());
  size_t n = 0;
  for (size_t i = 0; i < a.size(); ++i) n += std::memcmp(&a[i], &b[i], sizeof(float)) != 0;
  return n;
}

size_t differingBits(const std::vector<DVec3>& a, const std::vector<DVec3>& b) {
  if (a.size() != b.size()) return std::max(a.size(), b.size());
  size_t n = 0;
  for (size_t i = 0; i < a.size(); ++i) n += std::memcmp(&a[i], &b[i], sizeof(DVec3)) != 0;
  return n;
}

class Checkpoint : public ::testing::TestWithParam<std::string> {
 protected:
  static std::string suiteDir() {
    return (fs::path(::testing::TempDir()) / ("kasha_checkpoint." + std::to_string(getpid()))).string();
  }
  void SetUp() override {
    ASSERT_TRUE(fs::is_regular_file(test::kKashaBinary)) << "build the kasha target first";
    std::string name = ::testing::UnitTest::GetInstance()->current_test_info()->name();
    for (char& c : name)
      if (c == '/') c = '_';
    dir = suiteDir() + "/" + name;
    fs::remove_all(dir);
    fs::create_directories(dir);
    scene = dir + "/scene.json";
    std::ofstream(scene) << kScene;
  }
  void TearDown() override {
    if (!HasFailure()) fs::remove_all(dir);  // kept for inspection on failure
  }
  static void TearDownTestSuite() { fs::remove_all(suiteDir()); }

  // `kasha render scene` with the test's integrator, 2 threads, into dir/<name>.exr.
  std::vector<std::string> renderArgs(const std::string& name, std::vector<std::string> extra = {},
                                      const std::string& seed = "7") const {
    std::vector<std::string> a = {"render", scene, "-q", "--threads", "2", "--seed", seed, "--integrator", GetParam(),
                                  "-o", dir + "/" + name + ".exr"};
    a.insert(a.end(), extra.begin(), extra.end());
    return a;
  }

  json stats(const std::string& name) const { return json::parse(test::readTextFile(dir + "/" + name + ".stats.json")); }

  // An uninterrupted render with a final checkpoint: the reference, rendered once per integrator
  // and shared by the tests.
  std::string referenceDir() const { return suiteDir() + "/reference_" + GetParam(); }
  void renderReference() {
    const std::string ref = referenceDir();
    if (fs::exists(ref + "/reference.ckpt")) return;
    fs::create_directories(ref);
    std::vector<std::string> args = renderArgs("reference", {"--checkpoint", ref + "/reference.ckpt"});
    args[args.size() - 3] = ref + "/reference.exr";  // the -o argument
    const auto r = runKasha(args, ref + "/reference");
    ASSERT_EQ(r.code, 0) << r.err;
    ASSERT_EQ(json::parse(test::readTextFile(ref + "/reference.stats.json"))["spp"], kSpp);
  }

  // The resumed render equals the reference: film sums bit for bit, EXR floats bit for bit.
  void expectSameAsReference(const std::string& name) const {
    const CheckpointData ref = readCheckpoint(referenceDir() + "/reference.ckpt");
    const CheckpointData got = readCheckpoint(dir + "/" + name + ".ckpt");
    EXPECT_EQ(got.spp, kSpp);
    EXPECT_EQ(differingBits(got.sums, ref.sums), 0u) << "camera-sample sums differ";
    EXPECT_EQ(differingBits(got.splats, ref.splats), 0u) << "splat sums differ";
    const auto a = readExr(referenceDir() + "/reference.exr"), b = readExr(dir + "/" + name + ".exr");
    ASSERT_EQ(a.size(), 6u);
    for (const auto& [channel, values] : a) {
      ASSERT_TRUE(b.count(channel)) << channel;
      EXPECT_EQ(differingBits(values, b.at(channel)), 0u) << "EXR channel " << channel << " differs";
    }
    double sum = 0.0;
    for (float v : a.at("XYZ.Y")) sum += v;
    EXPECT_GT(sum, 0.0) << "the reference image is black: the comparison would prove little";
  }

  // Polls the checkpoint (replaced atomically, so every read sees a whole file) until it holds at
  // least `spp` samples per pixel.
  static void waitForCheckpoint(const std::string& ckpt, int spp) {
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(300);
    int saved = 0;
    while (saved < spp && std::chrono::steady_clock::now() < deadline) {
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
      if (fs::exists(ckpt)) saved = readCheckpoint(ckpt).spp;
    }
  }

  std::string dir, scene;
};

// Kill -9 a checkpointing render a third of the way through, resume it, compare.
TEST_P(Checkpoint, ResumeAfterSigkillIsBitIdentical) {
  renderReference();
  const std::string ckpt = dir + "/killed.ckpt";
  const test::Child c = test::spawnKasha(renderArgs("killed", {"--checkpoint", ckpt, "--checkpoint-interval", "0"}),
                                         dir + "/killed");
  ASSERT_GT(c.pid, 0);
  // A third of the samples in, kill.
  waitForCheckpoint(ckpt, kSpp / 3);
  ASSERT_EQ(kill(c.pid, SIGKILL), 0);
  const int status = test::waitChild(c, 60);
  ASSERT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == SIGKILL)
      << "the render finished before it could be killed; make the test scene slower";
  const int killedAt = readCheckpoint(ckpt).spp;
  EXPECT_GE(killedAt, kSpp / 3);
  EXPECT_LT(killedAt, kSpp) << "nothing left to resume";
  EXPECT_FALSE(fs::exists(dir + "/killed.exr"));

  const auto r = runKasha(renderArgs("killed", {"--resume", ckpt}), dir + "/resumed");
  ASSERT_EQ(r.code, 0) << r.err;
  const json st = stats("killed");
  EXPECT_EQ(st["spp"], kSpp);
  EXPECT_EQ(st["resumed"]["spp"], killedAt);
  EXPECT_EQ(st["samples"], uint64_t(kSpp - killedAt) * 32 * 32);  // only the samples of this run
  expectSameAsReference("killed");
}

// SIGINT: the image so far, its statistics and a checkpoint are written; exit code 130. Resuming
// that checkpoint completes the render to the reference's bits.
TEST_P(Checkpoint, SigintWritesImageStatsAndCheckpoint) {
  renderReference();
  const std::string ckpt = dir + "/stopped.ckpt";
  const test::Child c =
      test::spawnKasha(renderArgs("stopped", {"--checkpoint", ckpt, "--checkpoint-interval", "0"}), dir + "/stopped");
  ASSERT_GT(c.pid, 0);
  waitForCheckpoint(ckpt, 1);  // rendering has started
  ASSERT_EQ(kill(c.pid, SIGINT), 0);
  const int status = test::waitChild(c, 120);
  ASSERT_TRUE(WIFEXITED(status)) << "status " << status;
  EXPECT_EQ(WEXITSTATUS(status), 130) << test::readTextFile(c.err);
  EXPECT_CONTAINS(test::readTextFile(c.err), "stopping after the current pass");
  for (const char* ext : {".exr", ".png", ".stats.json"}) EXPECT_TRUE(fs::is_regular_file(dir + "/stopped" + ext)) << ext;
  const json st = stats("stopped");
  EXPECT_EQ(st["interrupted"], true);
  EXPECT_EQ(st["signal"], "SIGINT");
  const int spp = st["spp"];
  EXPECT_LT(spp, kSpp);
  EXPECT_EQ(spp % st["samples_per_pass"].get<int>(), 0) << "whole passes only";
  EXPECT_EQ(st["samples"], uint64_t(spp) * 32 * 32);
  ASSERT_TRUE(fs::is_regular_file(ckpt));
  EXPECT_EQ(readCheckpoint(ckpt).spp, spp);  // the last checkpoint is written on the way out
  EXPECT_FALSE(fs::exists(ckpt + ".tmp"));

  const auto r = runKasha(renderArgs("stopped", {"--resume", ckpt}), dir + "/resumed");
  ASSERT_EQ(r.code, 0) << r.err;
  expectSameAsReference("stopped");
}

INSTANTIATE_TEST_SUITE_P(Integrators, Checkpoint, ::testing::Values("pt", "lt"));

// The tests below do not depend on the integrator.
class CheckpointCli : public Checkpoint {};

TEST_P(CheckpointCli, SigtermExitsWith143) {
  const std::string ckpt = dir + "/term.ckpt";
  const test::Child c =
      test::spawnKasha(renderArgs("term", {"--checkpoint", ckpt, "--checkpoint-interval", "0"}), dir + "/term");
  ASSERT_GT(c.pid, 0);
  waitForCheckpoint(ckpt, 1);
  ASSERT_EQ(kill(c.pid, SIGTERM), 0);
  const int status = test::waitChild(c, 120);
  ASSERT_TRUE(WIFEXITED(status)) << "status " << status;
  EXPECT_EQ(WEXITSTATUS(status), 143);
  const json st = stats("term");
  EXPECT_EQ(st["interrupted"], true);
  EXPECT_EQ(st["signal"], "SIGTERM");
  EXPECT_TRUE(fs::is_regular_file(dir + "/term.exr"));
}

TEST_P(CheckpointCli, MismatchedOrDamagedCheckpointsAreRefused) {
  const std::string ckpt = dir + "/small.ckpt";
  auto r = runKasha(renderArgs("small", {"--spp", "64", "--checkpoint", ckpt}), dir + "/small");
  ASSERT_EQ(r.code, 0) << r.err;
  ASSERT_EQ(readCheckpoint(ckpt).spp, 64);

  auto expectRefused = [&](const std::vector<std::string>& extra, const std::string& reason, const std::string& seed = "7") {
    SCOPED_TRACE(reason);
    const auto f = runKasha(renderArgs("resumed", extra, seed), dir + "/resumed");
    EXPECT_EQ(f.code, 1) << f.err;
    const auto lines = test::textLines(f.err);
    ASSERT_EQ(lines.size(), 1u) << f.err;
    EXPECT_EQ(lines[0].rfind("kasha: error: ", 0), 0u) << lines[0];
    EXPECT_CONTAINS(lines[0], reason);
    EXPECT_FALSE(fs::exists(dir + "/resumed.exr"));
  };
  // Other settings than the checkpoint's.
  expectRefused({"--resume", ckpt}, ckpt + ": checkpoint was made with seed 7, this render has seed 8", "8");
  expectRefused({"--resume", ckpt, "--max-depth", "3"}, "max_depth");
  expectRefused({"--resume", ckpt, "--sensor-sampling", "uniform"}, "sensor_sampling");
  {
    std::ofstream(scene, std::ios::app) << "\n";  // the scene file changed
    expectRefused({"--resume", ckpt}, "scene_hash");
    std::ofstream(scene) << kScene;
  }
  // Missing, not a checkpoint, truncated, corrupted.
  expectRefused({"--resume", dir + "/none.ckpt"}, dir + "/none.ckpt: cannot open checkpoint file");
  expectRefused({"--resume", scene}, "not a kasha checkpoint");
  const std::string bytes = test::readTextFile(ckpt);
  std::ofstream(dir + "/truncated.ckpt", std::ios::binary) << bytes.substr(0, bytes.size() - 100);
  expectRefused({"--resume", dir + "/truncated.ckpt"}, "truncated");
  std::string flipped = bytes;
  flipped[bytes.size() / 2] ^= 0x10;
  std::ofstream(dir + "/corrupted.ckpt", std::ios::binary) << flipped;
  expectRefused({"--resume", dir + "/corrupted.ckpt"}, "corrupted");
  // A checkpoint directory that does not exist is a command-line mistake found before rendering.
  const auto noDir = runKasha(renderArgs("resumed", {"--checkpoint", dir + "/no/such/dir.ckpt"}), dir + "/resumed");
  EXPECT_EQ(noDir.code, 2) << noDir.err;
  EXPECT_CONTAINS(noDir.err, dir + "/no/such/dir.ckpt: --checkpoint: directory '" + dir + "/no/such' does not exist");
  EXPECT_FALSE(fs::exists(dir + "/resumed.exr"));

  // The same settings resume; a finished render can be continued to more samples.
  r = runKasha(renderArgs("more", {"--resume", ckpt, "--spp", "128"}), dir + "/more");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(stats("more")["spp"], 128);
  EXPECT_EQ(readCheckpoint(ckpt).spp, 128);  // --resume keeps checkpointing into its file
}

// Every setting that changes the estimator is in the checkpoint: a photon-mapping render resumed
// under other estimators of direct light (render.ppm.direct) would mix two estimators.
TEST_P(CheckpointCli, PhotonSettingsAreRecordedAndMustMatch) {
  const std::string ckpt = dir + "/ppm.ckpt";
  const std::vector<std::string> ppm = {"render", scene, "-q", "--threads", "2", "--integrator", "ppm"};
  auto args = ppm;
  args.insert(args.end(), {"--spp", "2", "-o", dir + "/ppm.exr", "--checkpoint", ckpt});
  const auto r = runKasha(args, dir + "/ppm");
  ASSERT_EQ(r.code, 0) << r.err;
  const json recorded = readCheckpoint(ckpt).settings;
  ASSERT_TRUE(recorded.contains("ppm")) << recorded.dump();
  EXPECT_EQ(recorded["ppm"]["direct"], "nee-elastic");
  EXPECT_TRUE(recorded["ppm"].contains("alpha"));
  args = ppm;
  args.insert(args.end(), {"-o", dir + "/ppm_resumed.exr", "--resume", ckpt, "--spp", "4", "--set", "ppm.direct=photons"});
  const auto f = runKasha(args, dir + "/ppm_resumed");
  EXPECT_EQ(f.code, 1) << f.err;
  EXPECT_CONTAINS(f.err, "checkpoint was made with ppm");
  EXPECT_CONTAINS(f.err, "\"direct\":\"photons\"");
  EXPECT_FALSE(fs::exists(dir + "/ppm_resumed.exr"));
}

// Every other setting of the estimator is recorded too: a resume under another is refused, naming
// it. Each case makes a checkpoint with its integrator (1 spp) and resumes it with one setting changed.
TEST_P(CheckpointCli, EveryEstimatorSettingIsRecordedAndMustMatch) {
  struct Case {
    std::string integrator;
    std::vector<std::string> changed;
    std::string field;
    std::vector<std::string> both = {};  // options of the checkpointed render and the resumed one
  };
  const std::vector<Case> cases = {
      {"pt", {"--integrator", "lt"}, "integrator"},
      {"pt", {"--sampler", "independent"}, "sampler"},
      {"pt", {"--hero", "2"}, "hero_wavelengths"},
      {"pt", {"--nee-sampling", "uniform"}, "nee_sampling", {"--hero", "1"}},  // one lane with either
      {"pt", {"--fluorescence-sampling", "uniform"}, "fluorescence_sampling"},
      {"pt", {"--spectral-bins", "4"}, "spectral_bins"},
      {"pt", {"--set", "rr_depth=5"}, "rr_depth"},
      {"pt", {"--set", "hide_emitters=true"}, "hide_emitters"},
      {"pt", {"--set", "fluorescent_lanes=end"}, "fluorescent_lanes"},
      {"lt", {"--light-sampling", "uniform"}, "light_sampling"},
      {"bdpt", {"--set", "bdpt.families=own"}, "bdpt"},
      {"vcm", {"--set", "vcm.paths=camera"}, "vcm"},
      {"vcm", {"--set", "vcm.radius=0.1"}, "vcm"},
      {"bdpt", {"--set", "bdpt.mollify_alpha=0.5"}, "bdpt", {"--set", "bdpt.families=own", "--set", "bdpt.mollify=true"}},
      {"ppm", {"--set", "ppm.nee_wavelengths=camera"}, "ppm"},
      {"ppm", {"--set", "ppm.always_wavelength_kernel=true"}, "ppm"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.integrator + " " + c.changed.back());
    std::string name = c.integrator;
    for (const std::string& o : c.both) name += o;
    const std::string ckpt = dir + "/" + name + ".ckpt";
    const auto args = [&](const std::string& out, std::vector<std::string> extra) {
      std::vector<std::string> a = {"render", scene, "-q", "--threads", "2", "-o", dir + "/" + out + ".exr"};
      a.insert(a.end(), c.both.begin(), c.both.end());
      if (std::find(extra.begin(), extra.end(), "--integrator") == extra.end()) extra.insert(extra.begin(), {"--integrator", c.integrator});
      a.insert(a.end(), extra.begin(), extra.end());
      return a;
    };
    if (!fs::exists(ckpt)) {
      const auto r = runKasha(args(name, {"--spp", "1", "--checkpoint", ckpt}), dir + "/" + name);
      ASSERT_EQ(r.code, 0) << r.err;
    }
    std::vector<std::string> resume = {"--spp", "2", "--resume", ckpt};
    resume.insert(resume.end(), c.changed.begin(), c.changed.end());
    const auto f = runKasha(args("resumed", resume), dir + "/resumed");
    EXPECT_EQ(f.code, 1) << f.err;
    const auto lines = test::textLines(f.err);
    ASSERT_EQ(lines.size(), 1u) << f.err;
    EXPECT_CONTAINS(lines[0], "kasha: error: " + ckpt + ": checkpoint was made with " + c.field + " ");
    EXPECT_FALSE(fs::exists(dir + "/resumed.exr"));
  }
}

// `original` (a checkpoint's bytes) with `header` as its JSON header, and the checksum of the
// format (hashBytes of every byte before it: a forger can compute it too) or a wrong one.
std::string forgeCheckpoint(const std::string& original, const std::string& header, bool rightChecksum) {
  uint64_t length = 0;
  std::memcpy(&length, original.data() + 16, sizeof length);
  std::string bytes = original.substr(0, 16);
  const uint64_t newLength = header.size();
  bytes.append(reinterpret_cast<const char*>(&newLength), sizeof newLength);
  bytes += header;
  bytes += original.substr(24 + length, original.size() - 24 - length - 8);
  const uint64_t sum = hashBytes(bytes.data(), bytes.size()) + (rightChecksum ? 0 : 1);
  bytes.append(reinterpret_cast<const char*>(&sum), sizeof sum);
  return bytes;
}

// Forged checkpoints: the checksum is verified over the whole file before the header is parsed,
// and a header with the right checksum is parsed within bounds (nesting, types, ranges). Each is
// refused with one line naming the file, never a crash.
TEST_P(CheckpointCli, ForgedHeadersAreRefusedInOneLine) {
  const std::string ckpt = dir + "/small.ckpt";
  const auto r = runKasha(renderArgs("small", {"--spp", "64", "--checkpoint", ckpt}), dir + "/small");
  ASSERT_EQ(r.code, 0) << r.err;
  const std::string original = test::readTextFile(ckpt);
  uint64_t length = 0;
  std::memcpy(&length, original.data() + 16, sizeof length);
  const json header = json::parse(original.substr(24, length));
  // The forger's file, resumed: one line naming it and the reason.
  auto expectRefused = [&](const std::string& name, const std::string& bytes, const std::string& reason) {
    SCOPED_TRACE(name);
    const std::string path = dir + "/" + name + ".ckpt";
    std::ofstream(path, std::ios::binary) << bytes;
    const auto f = runKasha(renderArgs("resumed", {"--resume", path}), dir + "/resumed");
    EXPECT_EQ(f.code, 1) << f.err;
    const auto lines = test::textLines(f.err);
    ASSERT_EQ(lines.size(), 1u) << f.err.substr(0, 2000);
    EXPECT_EQ(lines[0].rfind("kasha: error: " + path + ": ", 0), 0u) << lines[0];
    EXPECT_CONTAINS(lines[0], reason);
    EXPECT_FALSE(fs::exists(dir + "/resumed.exr"));
  };
  // Settings nested 100000 arrays deep (400 kB, within the header's 1 MiB).
  json deep = header;
  deep["settings"] = "NESTED";
  std::string nested = deep.dump();
  nested.replace(nested.find("\"NESTED\""), 8, std::string(100000, '[') + std::string(100000, ']'));
  expectRefused("nested_wrong_checksum", forgeCheckpoint(original, nested, false), "checksum mismatch");
  expectRefused("nested", forgeCheckpoint(original, nested, true), "nested deeper than 64 levels");
  // The right checksum, fields out of type or range.
  auto with = [&](const json::json_pointer& at, const json& value) {
    json h = header;
    h[at] = value;
    return forgeCheckpoint(original, h.dump(), true);
  };
  expectRefused("width_float", with("/film/width"_json_pointer, 1e300), "/film/width: expected an integer");
  expectRefused("width_huge", with("/film/width"_json_pointer, uint64_t(1) << 40), "/film/width: integer 1099511627776 is out of range");
  expectRefused("height_huge", with("/film/height"_json_pointer, 100000), "/film/height: 100000 is out of range");
  expectRefused("width_wrong", with("/film/width"_json_pointer, 33), "pixel count does not match the film size");
  expectRefused("spp_negative", with("/film/spp"_json_pointer, -5), "/film/spp: must not be negative");
  expectRefused("pixel_outside", with("/film/first_non_finite_pixel"_json_pointer, json{99999, 0}), "/film/first_non_finite_pixel");
  expectRefused("bins_huge", with("/film/spectral_bins"_json_pointer, json{{"min", 400}, {"step", 1}, {"count", 1 << 30}}),
                "spectral bins out of range");
  expectRefused("samples_per_pass_float", with("/run/samples_per_pass"_json_pointer, 1e300),
                "/run/samples_per_pass: expected an integer");
  expectRefused("seconds_string", with("/run/seconds"_json_pointer, "long"), "/run/seconds: expected a finite number");
  expectRefused("settings_array", with("/settings"_json_pointer, json::array()), "/settings: expected an object");
  std::string duplicate = header.dump();
  duplicate.insert(1, "\"byte_order\":\"little\",");
  expectRefused("duplicate_key", forgeCheckpoint(original, duplicate, true), "duplicate key 'byte_order'");
  expectRefused("not_json", forgeCheckpoint(original, "{\"settings\": [1, 2", true), "malformed JSON");
  // Lengths in the binary part: a header length beyond 1 MiB, a pixel count beyond the file.
  std::string longHeader = original;
  const uint64_t huge = uint64_t(1) << 62;
  std::memcpy(longHeader.data() + 16, &huge, sizeof huge);
  expectRefused("header_length", longHeader, "header length");
  std::string pixels = original;
  std::memcpy(pixels.data() + 24 + length, &huge, sizeof huge);
  const uint64_t sum = hashBytes(pixels.data(), pixels.size() - 8);
  std::memcpy(pixels.data() + pixels.size() - 8, &sum, sizeof sum);
  expectRefused("pixel_count", pixels, "truncated or has trailing data");
  // The unforged file still resumes.
  const auto ok = runKasha(renderArgs("more", {"--resume", ckpt, "--spp", "128"}), dir + "/more");
  EXPECT_EQ(ok.code, 0) << ok.err;
}

INSTANTIATE_TEST_SUITE_P(Cli, CheckpointCli, ::testing::Values("pt"));

}  // namespace
}  // namespace kasha
