#include "integrators/render_loop.h"

#include <tbb/blocked_range.h>
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>

namespace kasha {

int defaultSamplesPerPass(int width, int height) { return std::max(1, 65536 / std::max(1, width * height)); }

RenderStats render(const Scene& scene, const Integrator& integrator, Film& film, const RenderOptions& opt) {
  std::unique_ptr<tbb::global_control> limit;
  if (opt.threads > 0) limit = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism, size_t(opt.threads));
  const int w = film.width(), h = film.height();
  const auto start = std::chrono::steady_clock::now();
  auto elapsed = [&] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(); };
  RenderStats st;
  st.integrator = integrator.name();
  st.threads = int(tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism));
  const uint64_t seedMix = mixBits(opt.seed + 0x9e3779b97f4a7c15ULL);
  // The stream of a sample depends only on its index, not on how samples are grouped into passes.
  const int perPass = std::min(opt.samplesPerPass > 0 ? opt.samplesPerPass : defaultSamplesPerPass(w, h),
                               integrator.maxSamplesPerPass());
  st.samplesPerPass = perPass;
  constexpr int kTile = 16;
  const int tilesX = (w + kTile - 1) / kTile, tilesY = (h + kTile - 1) / kTile, tileCount = tilesX * tilesY;
  std::vector<SampleContext> contexts(static_cast<size_t>(tileCount));
  RayCounter passRays;  // traced by Integrator::beginPass
  auto stopRequested = [&] { return opt.stop && opt.stop->load() != 0; };
  // Statistics of this run so far; spp and the non-finite count are the film's totals.
  auto snapshot = [&](int pass) {
    st.seconds = elapsed();
    st.spp = pass;
    st.samples = uint64_t(pass - opt.startSpp) * uint64_t(w) * uint64_t(h);
    st.closestRays = passRays.closest;
    st.shadowRays = passRays.shadow;
    for (const SampleContext& ctx : contexts) {
      st.closestRays += ctx.counter.closest;
      st.shadowRays += ctx.counter.shadow;
    }
    st.rays = st.closestRays + st.shadowRays;
    st.samplesPerSecond = st.seconds > 0.0 ? double(st.samples) / st.seconds : 0.0;
    st.raysPerSecond = st.seconds > 0.0 ? double(st.rays) / st.seconds : 0.0;
    st.nonFiniteSamples = film.nonFiniteCount();
    return st;
  };
  int pass = std::max(0, opt.startSpp);
  film.setSamplesPerPixel(pass);
  double lastCheckpoint = 0.0;
  bool unsaved = false;
  while (pass < opt.spp) {
    if (stopRequested()) {
      st.interrupted = true;
      break;
    }
    const int first = pass, count = std::min(perPass, opt.spp - pass);
    const std::unique_ptr<const PassData> passData = integrator.beginPass(scene, first, count, opt.seed, passRays);
    // Fixed 16×16 tiles; each keeps its splats, merged in tile order so the sums do not depend
    // on scheduling.
    tbb::parallel_for(tbb::blocked_range<int>(0, tileCount, 1), [&](const tbb::blocked_range<int>& range) {
      for (int tile = range.begin(); tile < range.end(); ++tile) {
        SampleContext& ctx = contexts[size_t(tile)];
        ctx.splats.clear();
        ctx.strategies.clear();
        ctx.recordStrategies = bool(opt.strategies);
        ctx.pass = passData.get();
        const int x0 = (tile % tilesX) * kTile, y0 = (tile / tilesX) * kTile;
        for (int y = y0; y < std::min(y0 + kTile, h); ++y)
          for (int x = x0; x < std::min(x0 + kTile, w); ++x) {
            const uint64_t pixel = uint64_t(y) * uint64_t(w) + uint64_t(x);
            for (int s = first; s < first + count; ++s) {
              Sampler rng(opt.sampler, seedMix, pixel, uint32_t(s));
              film.add(x, y, integrator.samplePixel(scene, Vec2(float(x), float(y)), rng, ctx));
            }
          }
      }
    }, tbb::simple_partitioner());
    for (SampleContext& ctx : contexts)
      for (const Splat& sp : ctx.splats) {
        // A splat at a non-finite position is counted like a non-finite sample (pixel -1, -1).
        if (!std::isfinite(sp.pixel.x) || !std::isfinite(sp.pixel.y)) {
          film.addNonFinite(-1, -1);
          continue;
        }
        // Clamped as floats: converting a huge float to int would be undefined behaviour.
        const int x = int(std::clamp(sp.pixel.x, 0.0f, float(w - 1))), y = int(std::clamp(sp.pixel.y, 0.0f, float(h - 1)));
        film.addSplat(x, y, sp.xyz);
      }
    if (opt.strategies)
      for (const SampleContext& ctx : contexts)
        for (const StrategySample& r : ctx.strategies) opt.strategies(r);
    pass += count;
    film.setSamplesPerPixel(pass);
    unsaved = true;
    const double t = elapsed(), total = opt.previousSeconds + t;
    const bool outOfTime = opt.timeBudgetSeconds > 0.0 && total >= opt.timeBudgetSeconds;
    if (opt.progress) {
      double estimate = t * double(opt.spp - opt.startSpp) / double(pass - opt.startSpp);
      if (opt.timeBudgetSeconds > 0.0) estimate = std::min(estimate, std::max(opt.timeBudgetSeconds - opt.previousSeconds, t));
      if (outOfTime) estimate = t;
      opt.progress(pass, t, estimate);
    }
    if (outOfTime) break;
    if (opt.checkpoint && pass < opt.spp && t - lastCheckpoint >= opt.checkpointIntervalSeconds) {
      opt.checkpoint(snapshot(pass));
      lastCheckpoint = elapsed();
      unsaved = false;
    }
  }
  snapshot(pass);
  if (opt.checkpoint && unsaved) opt.checkpoint(st);
  return st;
}

}  // namespace kasha

namespace kasha {

nlohmann::json toJson(const RenderStats& s) {
  return {{"integrator", s.integrator},
          {"seconds", s.seconds},
          {"spp", s.spp},
          {"samples", s.samples},
          {"rays", s.rays},
          {"closest_hit_rays", s.closestRays},
          {"shadow_rays", s.shadowRays},
          {"samples_per_second", s.samplesPerSecond},
          {"rays_per_second", s.raysPerSecond},
          {"non_finite_samples", s.nonFiniteSamples},
          {"threads", s.threads},
          {"samples_per_pass", s.samplesPerPass},
          {"interrupted", s.interrupted}};
}

std::string summaryLine(const RenderStats& s) {
  char buf[256];
  std::snprintf(buf, sizeof buf, "%s: %.2f s, %d spp, %.3g samples/s, %.3g rays/s, %d threads%s%s", s.integrator.c_str(),
                s.seconds, s.spp, s.samplesPerSecond, s.raysPerSecond, s.threads,
                s.nonFiniteSamples ? (", " + std::to_string(s.nonFiniteSamples) + " non-finite samples dropped").c_str() : "",
                s.interrupted ? ", interrupted" : "");
  return buf;
}

}  // namespace kasha
