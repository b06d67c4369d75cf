// The render loop (integrators/render_loop.h) with scripted integrators: non-finite samples and
// splats never reach the film but are counted with a pixel; a stop request ends the render after
// a whole pass; checkpoint callbacks come at the requested cadence; and a render resumed from a
// film state at a pass boundary gives the same bits as an uninterrupted one. Checkpoint files
// round-trip the film's exact bits.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <limits>

#include "core/checkpoint.h"
#include "core/error.h"
#include "integrators/render_loop.h"

namespace kasha {
namespace {

namespace fs = std::filesystem;

// What ScriptedIntegrator prepares before a pass: depends on the pass's first sample and the
// seed only (as a photon map does), so a resumed render prepares the same.
struct ScriptedPass : PassData {
  float offset = 0.0f;
};

// Returns a random value, and a NaN or an infinity at chosen (pixel, sample)s.
class ScriptedIntegrator : public Integrator {
 public:
  std::unique_ptr<const PassData> beginPass(const Scene&, int firstSample, int count, uint64_t seed,
                                            RayCounter& counter) const override {
    auto p = std::make_unique<ScriptedPass>();
    p->offset = 0.001f * float(firstSample) + 0.01f * float(count) + float(seed % 7);
    ++counter.closest;
    return p;
  }
  Vec3 samplePixel(const Scene&, Vec2 pixel, Sampler& rng, SampleContext& ctx) const override {
    ++ctx.counter.closest;
    const float offset = static_cast<const ScriptedPass*>(ctx.pass)->offset;
    const int x = int(pixel.x), y = int(pixel.y);
    if (x == 5 && y == 3) return Vec3(std::numeric_limits<float>::quiet_NaN(), 1.0f, 1.0f);
    if (x == 6 && y == 3) return Vec3(0.0f, std::numeric_limits<float>::infinity(), 0.0f);
    if (splats) {
      // Splats to other pixels, some of them non-finite or off the film.
      const float u = rng.uniform(), v = rng.uniform();
      ctx.splats.push_back({Vec2(u * 40.0f - 4.0f, v * 20.0f), Vec3(rng.uniform(), 0.5f, 0.25f)});
      if (x == 1 && y == 1) ctx.splats.push_back({Vec2(2.0f, 2.0f), Vec3(std::numeric_limits<float>::infinity())});
      if (x == 2 && y == 1) ctx.splats.push_back({Vec2(std::numeric_limits<float>::quiet_NaN(), 2.0f), Vec3(1.0f)});
    }
    return Vec3(rng.uniform() + offset, rng.uniform(), rng.uniform());
  }
  std::string name() const override { return "scripted"; }
  bool splats = false;
};

// Requests a stop from inside the first sample of the render.
class StoppingIntegrator : public Integrator {
 public:
  explicit StoppingIntegrator(std::atomic<int>& flag) : flag_(flag) {}
  Vec3 samplePixel(const Scene&, Vec2, Sampler& rng, SampleContext&) const override {
    flag_.store(2);
    return Vec3(rng.uniform());
  }
  std::string name() const override { return "stopping"; }

 private:
  std::atomic<int>& flag_;
};

bool sameBits(const std::vector<DVec3>& a, const std::vector<DVec3>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(DVec3)) == 0;
}

TEST(RenderLoop, NonFiniteSamplesAreCountedNotAdded) {
  const Scene scene;
  ScriptedIntegrator integrator;
  integrator.splats = true;
  Film film(32, 16);
  RenderOptions opt;
  opt.spp = 4;
  opt.threads = 1;  // the first non-finite pixel is then the first in tile order
  const RenderStats st = render(scene, integrator, film, opt);
  // Two camera samples a pixel-sample (pixels (5,3) and (6,3)), plus from pixels (1,1) and
  // (2,1) one infinite splat and one splat at a NaN position, each sample.
  EXPECT_EQ(st.nonFiniteSamples, 4u * 4u);
  EXPECT_EQ(film.nonFiniteCount(), 16u);
  // One thread: tile 0's pixels in row order come first; splats are merged after the pass.
  EXPECT_EQ(film.firstNonFinitePixel(), std::make_pair(5, 3));
  for (int y = 0; y < film.height(); ++y)
    for (int x = 0; x < film.width(); ++x) {
      const Vec3 v = film.xyz(x, y);
      EXPECT_TRUE(std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z)) << x << ", " << y;
    }
  // The bad pixels hold only their splats.
  EXPECT_EQ(film.sampleSums()[3 * 32 + 5].x, 0.0);
  EXPECT_EQ(film.sampleSums()[3 * 32 + 6].y, 0.0);
  const nlohmann::json j = toJson(st);
  EXPECT_EQ(j["non_finite_samples"], 16);
  EXPECT_EQ(j["interrupted"], false);
}

TEST(RenderLoop, StopRequestEndsAfterAWholePass) {
  const Scene scene;
  std::atomic<int> stop{0};
  StoppingIntegrator integrator(stop);
  Film film(64, 64);  // 16 samples per pixel in a pass
  RenderOptions opt;
  opt.spp = 1000;
  opt.stop = &stop;
  int checkpoints = 0;
  opt.checkpoint = [&](const RenderStats& s) {
    ++checkpoints;
    EXPECT_EQ(s.spp, 16);
  };
  const RenderStats st = render(scene, integrator, film, opt);
  EXPECT_TRUE(st.interrupted);
  EXPECT_EQ(st.samplesPerPass, 16);
  EXPECT_EQ(st.spp, 16);
  EXPECT_EQ(film.samplesPerPixel(), 16);
  EXPECT_EQ(st.samples, 16u * 64 * 64);
  EXPECT_EQ(checkpoints, 1) << "the state at the stop is checkpointed";
  // A stop requested before the render starts renders nothing.
  Film idle(8, 8);
  const RenderStats none = render(scene, integrator, idle, opt);
  EXPECT_TRUE(none.interrupted);
  EXPECT_EQ(none.spp, 0);
}

TEST(RenderLoop, CheckpointCadence) {
  const Scene scene;
  ScriptedIntegrator integrator;
  Film film(64, 64);
  RenderOptions opt;
  opt.spp = 100;  // passes of 16: 16, 32, ..., 96, 100
  std::vector<int> at;
  opt.checkpoint = [&](const RenderStats& s) { at.push_back(s.spp); };
  opt.checkpointIntervalSeconds = 0.0;
  render(scene, integrator, film, opt);
  EXPECT_EQ(at, (std::vector<int>{16, 32, 48, 64, 80, 96, 100}));
  at.clear();
  opt.checkpointIntervalSeconds = 3600.0;
  Film film2(64, 64);
  render(scene, integrator, film2, opt);
  EXPECT_EQ(at, (std::vector<int>{100})) << "only the final state";
}

// The loop-level form of the kill-and-resume test (test_checkpoint.cpp has the process-level one).
TEST(RenderLoop, ResumedRenderIsBitIdentical) {
  const Scene scene;
  ScriptedIntegrator integrator;
  integrator.splats = true;
  RenderOptions opt;
  opt.spp = 200;  // 40×20 pixels: 81 samples per pass
  opt.seed = 9;
  Film full(40, 20);
  const RenderStats all = render(scene, integrator, full, opt);
  ASSERT_EQ(all.samplesPerPass, 81);

  // Stop after two passes, carry the state over to a new film (as a checkpoint does), continue.
  Film first(40, 20);
  RenderOptions part = opt;
  part.spp = 162;
  render(scene, integrator, first, part);
  Film resumed(40, 20);
  resumed.restore(first.sampleSums(), first.splatSums(), first.samplesPerPixel(), first.nonFiniteCount(),
                  first.firstNonFinitePixel());
  RenderOptions rest = opt;
  rest.startSpp = 162;
  rest.samplesPerPass = 81;
  const RenderStats st = render(scene, integrator, resumed, rest);
  EXPECT_EQ(st.spp, 200);
  EXPECT_EQ(st.samples, uint64_t(200 - 162) * 40 * 20);
  EXPECT_TRUE(sameBits(resumed.sampleSums(), full.sampleSums()));
  EXPECT_TRUE(sameBits(resumed.splatSums(), full.splatSums()));
  EXPECT_EQ(resumed.nonFiniteCount(), full.nonFiniteCount());
  // With another grouping into passes the splat sums (and here the pass data) differ: why the
  // checkpoint records the samples per pass.
  Film regrouped(40, 20);
  RenderOptions other = opt;
  other.samplesPerPass = 7;
  render(scene, integrator, regrouped, other);
  EXPECT_FALSE(sameBits(regrouped.sampleSums(), full.sampleSums()));
}

TEST(RenderLoop, TimeBudgetCountsPreviousRuns) {
  const Scene scene;
  ScriptedIntegrator integrator;
  Film film(64, 64);
  RenderOptions opt;
  opt.spp = 1000;
  opt.timeBudgetSeconds = 10.0;
  opt.previousSeconds = 10.0;  // already spent: one pass, then stop
  const RenderStats st = render(scene, integrator, film, opt);
  EXPECT_EQ(st.spp, 16);
  EXPECT_FALSE(st.interrupted);
}

class CheckpointFile : public ::testing::Test {
 protected:
  void SetUp() override {
    dir = (fs::path(::testing::TempDir()) / ("kasha_render_loop." + std::to_string(getpid()))).string();
    fs::create_directories(dir);
  }
  void TearDown() override { fs::remove_all(dir); }
  std::string dir;
};

TEST_F(CheckpointFile, RoundTripsTheFilmsBits) {
  const Scene scene;
  ScriptedIntegrator integrator;
  integrator.splats = true;
  Film film(40, 20);
  RenderOptions opt;
  opt.spp = 5;
  render(scene, integrator, film, opt);
  const std::string path = dir + "/a.ckpt";
  const nlohmann::json settings = {{"seed", 1}, {"integrator", "scripted"}};
  writeCheckpoint(path, settings, {{"samples_per_pass", 81}}, film);
  EXPECT_FALSE(fs::exists(path + ".tmp"));
  CheckpointData d = readCheckpoint(path);
  EXPECT_EQ(d.settings, settings);
  EXPECT_EQ(d.run["samples_per_pass"], 81);
  EXPECT_EQ(d.width, 40);
  EXPECT_EQ(d.height, 20);
  EXPECT_EQ(d.spp, 5);
  EXPECT_EQ(d.nonFiniteSamples, film.nonFiniteCount());
  EXPECT_EQ(d.firstNonFinitePixel, film.firstNonFinitePixel());
  EXPECT_TRUE(sameBits(d.sums, film.sampleSums()));
  EXPECT_TRUE(sameBits(d.splats, film.splatSums()));
  Film back(40, 20);
  restoreFilm(std::move(d), back);
  EXPECT_EQ(back.samplesPerPixel(), 5);
  EXPECT_EQ(back.xyz(7, 7), film.xyz(7, 7));
  // A film of another size is refused.
  Film other(20, 40);
  EXPECT_THROW(restoreFilm(readCheckpoint(path), other), InputError);
}

TEST_F(CheckpointFile, SettingsMustMatch) {
  const nlohmann::json saved = {{"seed", 1}, {"integrator", "pt"}};
  EXPECT_NO_THROW(requireSameSettings(saved, saved, "x.ckpt"));
  try {
    requireSameSettings(saved, {{"seed", 2}, {"integrator", "pt"}}, "x.ckpt");
    ADD_FAILURE() << "expected an InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()),
              "x.ckpt: checkpoint was made with seed 1, this render has seed 2; resume with the same scene and options");
  }
  EXPECT_THROW(requireSameSettings(saved, {{"seed", 1}}, "x.ckpt"), InputError);
  EXPECT_THROW(requireSameSettings(saved, {{"seed", 1}, {"integrator", "pt"}, {"new", 0}}, "x.ckpt"), InputError);
}

TEST(Hash, DependsOnEveryByte) {
  std::vector<unsigned char> bytes(1000);
  for (size_t i = 0; i < bytes.size(); ++i) bytes[i] = static_cast<unsigned char>(i * 7);
  const uint64_t h = hashBytes(bytes.data(), bytes.size());
  EXPECT_EQ(h, hashBytes(bytes.data(), bytes.size()));
  for (size_t i : {size_t(0), size_t(7), size_t(8), size_t(511), size_t(999)}) {
    for (int bit : {0, 7}) {
      bytes[i] ^= static_cast<unsigned char>(1 << bit);
      EXPECT_NE(hashBytes(bytes.data(), bytes.size()), h) << i << ":" << bit;
      bytes[i] ^= static_cast<unsigned char>(1 << bit);
    }
  }
  EXPECT_NE(hashBytes(bytes.data(), 999), hashBytes(bytes.data(), 1000));
  EXPECT_NE(hashBytes("", 0), hashBytes("\0", 1));
}

}  // namespace
}  // namespace kasha
