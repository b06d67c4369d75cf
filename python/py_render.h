#pragma once
// kasha.render(): renders a PyScene with any integrator and returns numpy arrays and statistics.
// The GIL is released while the render runs; between passes the render takes it back briefly to
// run Python's signal handlers (Ctrl-C) and the progress callback.
#include <pybind11/pybind11.h>

#include <cstdint>
#include <optional>
#include <string>

#include "core/memory_budget.h"

#include "python/py_scene.h"

namespace kasha::python {

// kasha.render's arguments, read and checked by python/py_arguments.h.
struct RenderRequest {
  std::optional<std::string> integrator;  // none: the scene's (render/integrator, else pt)
  std::optional<int> spp, seed;  // none: the scene's
  std::optional<double> time;
  int threads = 0;
  int spectralBins = 0;
  double spectralStep = 0.0;
  bool strategyImages = false;
  int strategyDepth = 4;
  uint64_t memoryLimit = kDefaultMemoryLimit;
  pybind11::object progress;  // None or callable(spp, seconds, estimated_total_seconds)
  std::string output;         // an OpenEXR to write as well (with the spectral bins)
  pybind11::dict settings;    // further keys of the scene's render object
};

// Returns a dict: xyz, rgb, stats, and spectral + wavelengths + bin_width (with bins) and
// strategies (with strategy images). Ctrl-C raises `interrupted` (a KeyboardInterrupt subclass)
// after the current pass, with the partial result as its `result` attribute. The render works on
// the scene as it is now: edits of `scene` and other renders of it, from other threads or from
// the progress callback, do not change it.
pybind11::dict render(PyScene& scene, const RenderRequest& request, const pybind11::object& interrupted);

}  // namespace kasha::python
