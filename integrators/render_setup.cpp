#include "integrators/render_setup.h"

#include <algorithm>
#include <stdexcept>
#include <string>

#include "core/film.h"
#include "core/memory_budget.h"
#include "core/sampler.h"
#include "integrators/render_pass.h"

namespace kasha {

void requireFilmMemory(int width, int height, const SpectralBins& bins, bool resuming, uint64_t limit) {
  const uint64_t sums = Film::bytesFor(width, height) + SpectralFilm::bytesFor(width, height, bins.count);
  const uint64_t channels = saturatingMul(uint64_t(width) * uint64_t(height) * sizeof(float), 6 + uint64_t(bins.count));
  requireMemory(saturatingMul(sums, resuming ? 2 : 1) + channels,
                "the film (" + std::to_string(width) + "x" + std::to_string(height) + " pixels" +
                    (bins.enabled() ? ", " + std::to_string(bins.count) + " spectral bins" : "") + ")",
                limit);
}

void requirePassMemory(const Integrator& integrator, int width, int height, int samplesPerPass, bool spectral,
                       uint64_t limit) {
  const int perPass =
      samplesPerPass > 0 ? samplesPerPass : std::min(defaultSamplesPerPass(width, height), integrator.maxSamplesPerPass());
  requireMemory(PassTracer::sampleBytes(width, height, perPass, spectral),
                "the samples of one pass (" + std::to_string(perPass) + " per pixel)", limit);
}

RenderOptions renderOptions(const RenderSettings& settings, int threads) {
  RenderOptions opt;
  opt.spp = settings.spp;
  opt.timeBudgetSeconds = settings.timeBudgetSeconds;
  opt.seed = settings.seed;
  opt.sampler = settings.sampler;
  opt.threads = threads;
  return opt;
}

nlohmann::json settingsRecord(const RenderSettings& r, const Integrator& integrator) {
  return {{"seed", r.seed},
          {"sampler", toString(r.sampler)},
          {"sensor_sampling", r.wavelengths.sensor.text},
          {"fluorescence_sampling", r.wavelengths.fluorescence.text},
          {"light_sampling", r.wavelengths.light.text},
          {"nee_sampling", r.wavelengths.nee.text},
          {"hero_wavelengths", integrator.lanes()},
          {"fluorescent_lanes", toString(r.fluorescentLanes)},
          {"max_depth", r.maxDepth}};
}

}  // namespace kasha
