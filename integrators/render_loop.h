#pragma once
// Runs an integrator over the image: passes of one sample per pixel over 16×16 tiles in
// parallel (TBB). Sample s of pixel (x, y) draws from its own PCG32 stream seeded by
// (seed, x, y, s), so the image does not depend on the number of threads.
#include <functional>
#include <string>

#include "core/film.h"
#include "integrators/integrator.h"

namespace kasha {

struct RenderOptions {
  int spp = 16;                  // stop after this many samples per pixel
  double timeBudgetSeconds = 0;  // > 0: stop after the first pass that ends past this time
  uint64_t seed = 1;
  int threads = 0;               // 0: all cores
  // Called after every pass with (samples per pixel so far, seconds so far, estimated total seconds).
  std::function<void(int, double, double)> progress;
};

struct RenderStats {
  std::string integrator;
  double seconds = 0.0;
  int spp = 0;
  uint64_t samples = 0, rays = 0, closestRays = 0, shadowRays = 0;
  double samplesPerSecond = 0.0, raysPerSecond = 0.0;
  uint64_t nonFiniteSamples = 0;
  int threads = 0;
};

RenderStats render(const Scene& scene, const Integrator& integrator, Film& film, const RenderOptions& options);

}  // namespace kasha

#include <nlohmann/json.hpp>

namespace kasha {
nlohmann::json toJson(const RenderStats& s);
// One line for the terminal: time, spp, samples/s, rays/s.
std::string summaryLine(const RenderStats& s);
}  // namespace kasha
