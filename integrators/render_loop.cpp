#include "integrators/render_loop.h"

#include <tbb/global_control.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cstdio>
#include <memory>
#include <stdexcept>
#include <string>

#include "integrators/rank_agreement.h"

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
  const int rank = opt.group ? opt.group->rank() : 0;
  st.ranks = opt.group ? opt.group->size() : 1;
  const bool root = rank == 0;
  // The stream of a sample depends only on its index, not on how samples are grouped into passes.
  const int perPass = std::min(opt.samplesPerPass > 0 ? opt.samplesPerPass : defaultSamplesPerPass(w, h),
                               integrator.maxSamplesPerPass());
  if (opt.group) {  // the group's first exchange: every rank renders the same passes of the same image
    nlohmann::json record = opt.image;
    record.update({{"spp", opt.spp}, {"time", opt.timeBudgetSeconds}, {"seed", opt.seed},
                   {"sampler", toString(opt.sampler)}, {"start_spp", opt.startSpp}, {"samples_per_pass", perPass},
                   {"resolution", {w, h}}, {"strategy_images", bool(opt.strategies)},
                   {"spectral", opt.spectral != nullptr}});
    requireSameRecord(*opt.group, record);
  }
  st.samplesPerPass = perPass;
  PassTracer tracer(scene, integrator, w, h, opt.seed, opt.sampler, bool(opt.strategies), opt.spectral != nullptr);
  RayCounter rays;  // of the committed passes: on rank 0, those of every rank
  auto commit = [&](const PassRecord& rec) {
    tracer.commit(rec, film, opt.spectral, opt.strategies);
    rays.closest += rec.rays.closest;
    rays.shadow += rec.rays.shadow;
  };
  // Agreed by all ranks after the same pass: the highest stop request and whether rank 0's time
  // budget is spent.
  auto agree = [&](int stop, bool outOfTime) {
    std::array<int, 2> v{stop, outOfTime ? 1 : 0};
    if (opt.group) opt.group->maxOverRanks(v);
    return v;
  };
  // Statistics of this run so far; spp and the non-finite count are the film's totals.
  auto snapshot = [&](int pass) {
    st.seconds = elapsed();
    st.spp = pass;
    st.samples = uint64_t(pass - opt.startSpp) * uint64_t(w) * uint64_t(h);
    st.closestRays = rays.closest;
    st.shadowRays = rays.shadow;
    st.rays = st.closestRays + st.shadowRays;
    st.samplesPerSecond = st.seconds > 0.0 ? double(st.samples) / st.seconds : 0.0;
    st.raysPerSecond = st.seconds > 0.0 ? double(st.rays) / st.seconds : 0.0;
    st.nonFiniteSamples = film.nonFiniteCount();
    st.choices = integrator.choices();
    return st;
  };
  int pass = std::max(0, opt.startSpp);
  film.setSamplesPerPixel(pass);
  if (opt.spectral) {
    if (opt.spectral->width() != w || opt.spectral->height() != h)
      throw std::invalid_argument("render: the spectral film's size differs from the film's");
    opt.spectral->setSamplesPerPixel(pass);
  }
  double lastCheckpoint = 0.0;
  bool unsaved = false;
  PassRecord local;  // this rank's passes, its buffers reused from pass to pass
  while (pass < opt.spp) {
    const int stop = agree(opt.stop ? opt.stop->load() : 0, false)[0];
    if (stop != 0) {
      st.interrupted = true;
      st.stopSignal = stop;
      break;
    }
    // One round: its k-th pass goes to rank k; rank 0 commits them in pass order.
    auto firstOf = [&](int k) { return int64_t(pass) + int64_t(k) * perPass; };
    if (firstOf(rank) < opt.spp) {
      const int first = int(firstOf(rank));
      tracer.trace(first, std::min(perPass, opt.spp - first), local);
      if (root)
        commit(local);
      else
        opt.group->send(local);
    }
    if (root)
      for (int k = 1; k < st.ranks && firstOf(k) < opt.spp; ++k) {
        const PassRecord rec = opt.group->receive(k, w, h);
        if (rec.first != firstOf(k))
          throw std::runtime_error("rank " + std::to_string(k) + " sent the pass of sample " + std::to_string(rec.first) +
                                   " instead of " + std::to_string(firstOf(k)));
        commit(rec);
      }
    pass = int(std::min<int64_t>(opt.spp, firstOf(st.ranks)));
    film.setSamplesPerPixel(pass);
    if (opt.spectral) opt.spectral->setSamplesPerPixel(pass);
    unsaved = true;
    const double t = elapsed(), total = opt.previousSeconds + t;
    const bool outOfTime = agree(0, root && opt.timeBudgetSeconds > 0.0 && total >= opt.timeBudgetSeconds)[1] != 0;
    if (root && opt.progress) {
      double estimate = t * double(opt.spp - opt.startSpp) / double(pass - opt.startSpp);
      if (opt.timeBudgetSeconds > 0.0) estimate = std::min(estimate, std::max(opt.timeBudgetSeconds - opt.previousSeconds, t));
      if (outOfTime) estimate = t;
      opt.progress(pass, t, estimate);
    }
    if (outOfTime) break;
    if (root && opt.checkpoint && pass < opt.spp && t - lastCheckpoint >= opt.checkpointIntervalSeconds) {
      opt.checkpoint(snapshot(pass));
      lastCheckpoint = elapsed();
      unsaved = false;
    }
  }
  snapshot(pass);
  if (root && opt.checkpoint && unsaved) opt.checkpoint(st);
  return st;
}

}  // namespace kasha

namespace kasha {

nlohmann::json toJson(const RenderStats& s) {
  nlohmann::json j = {{"integrator", s.integrator},
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
          {"interrupted", s.interrupted},
          {"ranks", s.ranks}};
  if (!s.choices.empty()) j["choices"] = s.choices;
  return j;
}

std::string summaryLine(const RenderStats& s) {
  char buf[256];
  std::snprintf(buf, sizeof buf, "%s: %.2f s, %d spp, %.3g samples/s, %.3g rays/s, %d threads%s%s%s", s.integrator.c_str(),
                s.seconds, s.spp, s.samplesPerSecond, s.raysPerSecond, s.threads,
                s.ranks > 1 ? (" x " + std::to_string(s.ranks) + " processes").c_str() : "",
                s.nonFiniteSamples ? (", " + std::to_string(s.nonFiniteSamples) + " non-finite samples dropped").c_str() : "",
                s.interrupted ? ", interrupted" : "");
  if (!s.choices.empty()) return std::string(buf) + "; " + s.choices;
  return buf;
}

}  // namespace kasha
