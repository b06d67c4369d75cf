#include "integrators/render_loop.h"

#include <tbb/blocked_range2d.h>
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
  std::atomic<uint64_t> closest{0}, shadow{0};
  RenderStats st;
  st.integrator = integrator.name();
  st.threads = int(tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism));
  const uint64_t seedMix = mixBits(opt.seed + 0x9e3779b97f4a7c15ULL);
  // A pass is at least ~64k samples, so small images keep every core busy; the stream of a sample
  // depends only on its index, not on how samples are grouped into passes.
  const int perPass = std::max(1, 65536 / std::max(1, w * h));
  int pass = 0;
  while (pass < opt.spp) {
    const int first = pass, count = std::min(perPass, opt.spp - pass);
    tbb::parallel_for(tbb::blocked_range2d<int>(0, h, 16, 0, w, 16), [&](const tbb::blocked_range2d<int>& r) {
      RayCounter counter;
      for (int y = r.rows().begin(); y < r.rows().end(); ++y)
        for (int x = r.cols().begin(); x < r.cols().end(); ++x) {
          const uint64_t pixel = uint64_t(y) * uint64_t(w) + uint64_t(x);
          for (int s = first; s < first + count; ++s) {
            Rng rng(mixBits(seedMix ^ mixBits(pixel)), uint64_t(s));
            film.add(x, y, integrator.samplePixel(scene, Vec2(float(x), float(y)), rng, counter));
          }
        }
      closest.fetch_add(counter.closest, std::memory_order_relaxed);
      shadow.fetch_add(counter.shadow, std::memory_order_relaxed);
    });
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
  st.closestRays = closest.load();
  st.shadowRays = shadow.load();
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
