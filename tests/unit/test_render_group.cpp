// The render loop dealing passes among the ranks of a group (integrators/render_group.h), the
// ranks being threads (thread_group.h): rank 0's film and spectral bins hold exactly the bits of
// a one-process render, its statistics the sums over the ranks, and a stop request on one rank ends every rank
// after the same pass. The MPI form of these tests runs the kasha binary under mpirun
// (tests/mpi/mpi_render_test.sh).
#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <cstring>
#include <memory>
#include <thread>

#include "integrators/render_loop.h"
#include "tests/thread_group.h"

namespace kasha {
namespace {

// Random camera samples and splats spanning 2^±60, so that their double sums depend on the
// order of the additions (floats of similar size add exactly in a double and would not tell);
// requests a stop through `stop` in the pass that starts at sample `stopAt` (as a signal
// arriving while that pass runs). With spectral bins, each sample records 0–2 shares of equally
// wide range and each splat one (sensorResponse, spectralSplat).
class SplattingIntegrator : public Integrator {
 public:
  std::unique_ptr<const PassData> beginPass(const Scene&, int firstSample, int, uint64_t, RayCounter& counter) const override {
    counter.shadow += 3;
    if (firstSample == stopAt && stop) stop->store(15);
    return nullptr;
  }
  Vec3 samplePixel(const Scene&, Vec2 pixel, Sampler& rng, SampleContext& ctx) const override {
    ++ctx.counter.closest;
    const float u = rng.uniform();
    if (u < 0.5f) ctx.splats.push_back(spectralSplat(Vec2(rng.uniform() * 24.0f, pixel.x), 400.0f + 300.0f * u, wide(rng)));
    Vec3 xyz(wide(rng), wide(rng) * pixel.y, u);
    for (int k = int(u * 3.0f); k > 0; --k) xyz += sensorResponse(ctx, 400.0f + 300.0f * rng.uniform(), wide(rng));
    return xyz;
  }
  static float wide(Sampler& rng) { return std::ldexp(rng.uniform(), int(rng.uniform() * 120.0f) - 60); }
  std::string name() const override { return "splatting"; }
  int stopAt = -1;
  std::atomic<int>* stop = nullptr;
};

bool sameBits(const std::vector<DVec3>& a, const std::vector<DVec3>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(DVec3)) == 0;
}

struct GroupRun {
  std::vector<std::unique_ptr<Film>> films;
  std::vector<std::unique_ptr<SpectralFilm>> spectral;  // only when rendering with bins
  std::vector<RenderStats> stats;
};

// Renders with `ranks` threads as ranks; rank r's integrator requests a stop at sample stopAt[r].
// With `bins`, every rank keeps spectral bins too.
GroupRun renderInGroup(int ranks, const RenderOptions& base, int width, int height, const std::vector<int>& stopAt = {},
                       const SpectralBins& bins = {}) {
  const Scene scene;
  test::ThreadGroup group(ranks);
  GroupRun run;
  run.stats.resize(size_t(ranks));
  for (int r = 0; r < ranks; ++r) {
    run.films.push_back(std::make_unique<Film>(width, height));
    if (bins.enabled()) run.spectral.push_back(std::make_unique<SpectralFilm>(width, height, bins));
  }
  std::vector<std::atomic<int>> stops(static_cast<size_t>(ranks));
  std::vector<std::thread> threads;
  for (int r = 0; r < ranks; ++r)
    threads.emplace_back([&, r] {
      SplattingIntegrator integrator;
      integrator.stop = &stops[size_t(r)];
      if (size_t(r) < stopAt.size()) integrator.stopAt = stopAt[size_t(r)];
      test::ThreadGroup::Rank rank(group, r);
      RenderOptions opt = base;
      opt.group = &rank;
      opt.stop = &stops[size_t(r)];
      if (bins.enabled()) opt.spectral = run.spectral[size_t(r)].get();
      run.stats[size_t(r)] = render(scene, integrator, *run.films[size_t(r)], opt);
    });
  for (std::thread& t : threads) t.join();
  return run;
}

TEST(RenderGroup, RanksGiveTheBitsOfOneProcess) {
  const Scene scene;
  SplattingIntegrator integrator;
  RenderOptions opt;
  opt.spp = 50;
  opt.samplesPerPass = 7;  // 8 passes, the last of 1 sample
  opt.seed = 5;
  const SpectralBins bins{400.0f, 30.0f, 10};
  Film one(24, 20);
  SpectralFilm oneBins(24, 20, bins);
  opt.spectral = &oneBins;
  const RenderStats single = render(scene, integrator, one, opt);
  opt.spectral = nullptr;
  double binTotal = 0.0;
  for (double v : oneBins.sums()) binTotal += std::abs(v);
  ASSERT_GT(binTotal, 0.0) << "the bins received shares";
  for (int ranks : {2, 3, 5}) {
    SCOPED_TRACE(ranks);
    const GroupRun run = renderInGroup(ranks, opt, 24, 20, {}, bins);
    EXPECT_TRUE(sameBits(run.films[0]->sampleSums(), one.sampleSums()));
    EXPECT_TRUE(sameBits(run.films[0]->splatSums(), one.splatSums()));
    const std::vector<double>& got = run.spectral[0]->sums();
    ASSERT_EQ(got.size(), oneBins.sums().size());
    EXPECT_EQ(std::memcmp(got.data(), oneBins.sums().data(), got.size() * sizeof(double)), 0) << "spectral bins";
    EXPECT_EQ(run.spectral[0]->samplesPerPixel(), 50);
    EXPECT_EQ(run.films[0]->samplesPerPixel(), 50);
    const RenderStats& st = run.stats[0];
    EXPECT_EQ(st.ranks, ranks);
    EXPECT_EQ(st.spp, 50);
    EXPECT_EQ(st.samples, single.samples);
    EXPECT_EQ(st.closestRays, single.closestRays) << "summed over the ranks";
    EXPECT_EQ(st.shadowRays, single.shadowRays) << "beginPass of every rank";
    // The other ranks' films receive nothing.
    for (int r = 1; r < ranks; ++r) EXPECT_EQ(run.films[size_t(r)]->sampleSums()[0].x, 0.0);
  }
}

TEST(RenderGroup, StopOnOneRankEndsAllAfterTheSamePass) {
  RenderOptions opt;
  opt.spp = 1000;
  opt.samplesPerPass = 4;
  // Two ranks: rank 1 traces the passes at samples 4, 12, 20, ...; it is signalled in the one at 20,
  // so the round of passes 16 and 20 is finished and every rank stops at 24.
  const GroupRun run = renderInGroup(2, opt, 16, 8, {-1, 20});
  for (const RenderStats& st : run.stats) {
    EXPECT_TRUE(st.interrupted);
    EXPECT_EQ(st.stopSignal, 15);
    EXPECT_EQ(st.spp, 24);
  }
  // The partial image is that of one process rendering 24 samples.
  const Scene scene;
  SplattingIntegrator integrator;
  Film one(16, 8);
  RenderOptions single = opt;
  single.spp = 24;
  render(scene, integrator, one, single);
  EXPECT_TRUE(sameBits(run.films[0]->sampleSums(), one.sampleSums()));
  EXPECT_TRUE(sameBits(run.films[0]->splatSums(), one.splatSums()));
}

}  // namespace
}  // namespace kasha
