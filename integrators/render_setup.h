#pragma once
// What every front end (the command line, the Python module) does around render(): checking the
// film's and a pass's memory, render options from the settings, and the settings a statistics record names.
#include <cstdint>

#include <nlohmann/json.hpp>

#include "core/spectral_film.h"
#include "integrators/integrator.h"
#include "integrators/render_loop.h"
#include "scene/render_settings.h"

namespace kasha {

// Checks the film's buffers against `limit` before they are allocated: the XYZ sums and the
// spectral bins (twice while a checkpoint is read into them) and the output's float channels (six
// and one per bin). Throws MemoryLimitError naming the resolution and bins.
void requireFilmMemory(int width, int height, const SpectralBins& bins, bool resuming, uint64_t limit);

// Checks a pass's sample record (integrators/render_pass.h) against `limit`: `samplesPerPass` per
// pixel, 0 for the default the integrator allows. Throws MemoryLimitError.
void requirePassMemory(const Integrator& integrator, int width, int height, int samplesPerPass, bool spectral,
                       uint64_t limit);

// The stop conditions (spp, time), seed and sampler of the settings, with `threads` (0: all cores).
RenderOptions renderOptions(const RenderSettings& settings, int threads);

// The settings a statistics record names: seed, sampler, the four wavelength strategies, the
// integrator's wavelength lanes (hero_wavelengths) and maximum depth.
nlohmann::json settingsRecord(const RenderSettings& settings, const Integrator& integrator);

}  // namespace kasha
