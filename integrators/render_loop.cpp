#include "integrators/render_loop.h"

#include <tbb/blocked_range.h>
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <memory>

namespace kasha {

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
  // A pass is at least ~64k samples, so small images keep every core busy; the stream of a sample
  // depends only on its index, not on how samples are grouped into passes.
  const int perPass = std::max(1, 65536 / std::max(1, w * h));
  constexpr int kTile = 16;
  const int tilesX = (w + kTile - 1) / kTile, tilesY = (h + kTile - 1) / kTile, tileCount = tilesX * tilesY;
  std::vector<SampleContext> contexts(static_cast<size_t>(tileCount));
  int pass = 0;
  while (pass < opt.spp) {
    const int first = pass, count = std::min(perPass, opt.spp - pass);
    // Fixed 16×16 tiles; each keeps its splats, merged in tile order so the sums do not depend
    // on scheduling.
    tbb::parallel_for(tbb::blocked_range<int>(0, tileCount, 1), [&](const tbb::blocked_range<int>& range) {
      for (int tile = range.begin(); tile < range.end(); ++tile) {
        SampleContext& ctx = contexts[size_t(tile)];
        ctx.splats.clear();
        const int x0 = (tile % tilesX) * kTile, y0 = (tile / tilesX) * kTile;
        for (int y = y0; y < std::min(y0 + kTile, h); ++y)
          for (int x = x0; x < std::min(x0 + kTile, w); ++x) {
            const uint64_t pixel = uint64_t(y) * uint64_t(w) + uint64_t(x);
            for (int s = first; s < first + count; ++s) {
              Rng rng(mixBits(seedMix ^ mixBits(pixel)), uint64_t(s));
              film.add(x, y, integrator.samplePixel(scene, Vec2(float(x), float(y)), rng, ctx));
            }
          }
      }
    }, tbb::simple_partitioner());
    for (SampleContext& ctx : contexts)
      for (const Splat& sp : ctx.splats) {
        const int x = std::clamp(int(sp.pixel.x), 0, w - 1), y = std::clamp(int(sp.pixel.y), 0, h - 1);
        film.addSplat(x, y, sp.xyz);
      }
    pass += count;
    film.setSamplesPerPixel(pass);
    const double t = elapsed();
    const bool outOfTime = opt.timeBudgetSeconds > 0.0 && t >= opt.timeBudgetSeconds;
    if (opt.progress) {
      double total = t * double(opt.spp) / double(pass);
      if (opt.timeBudgetSeconds > 0.0) total = std::min(total, std::max(opt.timeBudgetSeconds, t));
      if (outOfTime) total = t;
      opt.progress(pass, t, total);
    }
    if (outOfTime) break;
  }
  st.seconds = elapsed();
  st.spp = pass;
  st.samples = uint64_t(pass) * uint64_t(w) * uint64_t(h);
  for (const SampleContext& ctx : contexts) {
    st.closestRays += ctx.counter.closest;
    st.shadowRays += ctx.counter.shadow;
  }
  st.rays = st.closestRays + st.shadowRays;
  st.samplesPerSecond = st.seconds > 0.0 ? double(st.samples) / st.seconds : 0.0;
  st.raysPerSecond = st.seconds > 0.0 ? double(st.rays) / st.seconds : 0.0;
  st.nonFiniteSamples = film.nonFiniteCount();
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
          {"threads", s.threads}};
}

std::string summaryLine(const RenderStats& s) {
  char buf[256];
  std::snprintf(buf, sizeof buf, "%s: %.2f s, %d spp, %.3g samples/s, %.3g rays/s, %d threads%s", s.integrator.c_str(),
                s.seconds, s.spp, s.samplesPerSecond, s.raysPerSecond, s.threads,
                s.nonFiniteSamples ? (", " + std::to_string(s.nonFiniteSamples) + " non-finite samples dropped").c_str() : "");
  return buf;
}

}  // namespace kasha
