#include "python/py_render.h"

#include <atomic>
#include <optional>

#include "core/error.h"
#include "core/image_output.h"
#include "core/memory_budget.h"
#include "core/output_file.h"
#include "core/spectral_film.h"
#include "integrators/bdpt/bdpt_integrator.h"
#include "integrators/bdpt/strategy_images.h"
#include "integrators/integrator_factory.h"
#include "integrators/render_loop.h"
#include "integrators/render_setup.h"
#include "python/py_arrays.h"

namespace py = pybind11;

namespace kasha::python {
namespace {

// The scene's JSON with the request's settings in its render object. A time budget alone decides
// when to stop, as on the command line.
nlohmann::json withSettings(const nlohmann::json& scene, const RenderRequest& r) {
  nlohmann::json j = scene;
  nlohmann::json& render = j["render"];
  if (!render.is_object()) render = nlohmann::json::object();
  for (const auto& [key, value] : r.settings) render[py::str(key).cast<std::string>()] = toJson(value);
  if (!r.spp.is_none()) render["spp"] = toJson(r.spp);
  if (!r.time.is_none()) {
    render["time"] = toJson(r.time);
    if (r.spp.is_none()) render["spp"] = 1 << 30;
  }
  if (!r.seed.is_none()) render["seed"] = toJson(r.seed);
  return j;
}

SpectralBins binsFor(const Scene& scene, const RenderRequest& r) {
  if (r.spectralBins < 0 || !(r.spectralStep >= 0.0f))
    throw py::value_error("spectral_bins and spectral_step must be positive (0: no spectral bins)");
  if (r.spectralBins > 0 && r.spectralStep > 0.0f) throw py::value_error("give spectral_bins or spectral_step, not both");
  if (r.spectralBins > 0) return SpectralBins::fromCount(scene.range, r.spectralBins);
  if (r.spectralStep > 0.0f) return SpectralBins::fromStep(scene.range, r.spectralStep);
  return {};
}

py::array_t<float> binCentres(const SpectralBins& b) {
  py::array_t<float> a(b.count);
  for (int i = 0; i < b.count; ++i) a.mutable_at(i) = b.centre(i);
  return a;
}

}  // namespace

py::dict render(PyScene& pyScene, const RenderRequest& req, const py::object& interrupted) {
  const uint64_t memoryLimit = parseByteSize(req.memoryLimit);
  const Scene& scene = pyScene.load(withSettings(pyScene.json(), req), memoryLimit);
  RenderSettings settings = scene.render;
  settings.memoryLimit = memoryLimit;
  std::unique_ptr<Integrator> integrator = makeIntegrator(req.integrator, scene, settings);
  const int w = scene.camera.width(), h = scene.camera.height();
  const SpectralBins bins = binsFor(scene, req);
  // As on the command line, the output is checked before the first sample (core/output_file.h).
  if (!req.output.empty()) checkOutputs({{req.output, "output", ".exr", ""}});
  requireFilmMemory(w, h, bins, false, memoryLimit);
  requirePassMemory(*integrator, w, h, 0, bins.enabled(), memoryLimit);
  std::unique_ptr<bdpt::StrategyImages> strategies;
  if (req.strategyImages) {
    if (!dynamic_cast<const Bdpt*>(integrator.get()))
      throw py::value_error("strategy_images: only the BDPT integrators have (s, t) strategies, not '" + req.integrator + "'");
    requireMemory(bdpt::StrategyImages::bytesFor(w, h, req.strategyDepth), "the strategy images", memoryLimit);
    strategies = std::make_unique<bdpt::StrategyImages>(w, h, req.strategyDepth);
  }
  Film film(w, h);
  std::unique_ptr<SpectralFilm> spectral;
  if (bins.enabled()) spectral = std::make_unique<SpectralFilm>(w, h, bins);

  RenderOptions opt = renderOptions(settings, req.threads);
  opt.spectral = spectral.get();
  if (strategies) opt.strategies = [&](const StrategySample& r) { strategies->add(r); };
  std::atomic<int> stop{0};
  opt.stop = &stop;
  // Between passes: Python's signal handlers (a KeyboardInterrupt stops the render after this
  // pass), then the progress callback (an exception from it stops the render and is re-raised).
  std::optional<py::error_already_set> pending;
  bool keyboardInterrupt = false;
  opt.progress = [&](int spp, double seconds, double total) {
    py::gil_scoped_acquire gil;
    if (pending) return;
    if (PyErr_CheckSignals() != 0) {
      pending.emplace();
      keyboardInterrupt = pending->matches(PyExc_KeyboardInterrupt);
      stop.store(1);
      return;
    }
    if (req.progress.is_none()) return;
    try {
      req.progress(spp, seconds, total);
    } catch (py::error_already_set& e) {
      keyboardInterrupt = e.matches(PyExc_KeyboardInterrupt);
      pending.emplace(std::move(e));
      stop.store(1);
    }
  };
  RenderStats stats;
  {
    py::gil_scoped_release release;
    stats = render(scene, *integrator, film, opt);
  }
  if (!req.output.empty()) writeExr(film, req.output, spectral.get());

  py::dict result;
  result["xyz"] = xyzArray(film);
  result["rgb"] = rgbArray(result["xyz"].cast<py::array_t<float>>());
  nlohmann::json st = toJson(stats);
  st.update(settingsRecord(settings, *integrator));
  result["stats"] = fromJson(st);
  if (spectral) {
    result["spectral"] = spectralArray(*spectral);
    result["wavelengths"] = binCentres(bins);
    result["bin_width"] = bins.step;
  }
  if (strategies) {
    strategies->setSamplesPerPixel(film.samplesPerPixel());
    py::dict images;
    for (const auto& [name, img] : strategies->images()) {
      images[py::str(name)] = xyzArray(img->weighted);
      images[py::str(name + "_unweighted")] = xyzArray(img->unweighted);
    }
    result["strategies"] = images;
  }
  if (pending) {
    if (!keyboardInterrupt) throw std::move(*pending);
    py::object e = interrupted(py::str("render interrupted after " + std::to_string(stats.spp) +
                                       " samples per pixel; the partial result is in .result"));
    e.attr("result") = result;
    PyErr_SetObject(interrupted.ptr(), e.ptr());
    throw py::error_already_set();
  }
  return result;
}

}  // namespace kasha::python
