#include "python/py_render.h"

#include <atomic>
#include <optional>

#include "core/error.h"
#include "core/image_output.h"
#include "core/output_file.h"
#include "integrators/photon_mapping/direct_light_wavelengths.h"
#include "integrators/integrator_factory.h"
#include "integrators/render_job.h"
#include "python/py_arrays.h"
#include "scene/render_overrides.h"
#include "scene/render_settings.h"
#include "scene/wavelength_strategy.h"

namespace py = pybind11;

namespace kasha::python {
namespace {

// The scene's JSON with the request's settings in its render object (scene/render_overrides.h, as
// `kasha render --set`). A time budget alone decides when to stop, as on the command line.
nlohmann::json withSettings(const PyScene& scene, const std::vector<RenderSetting>& set, const RenderRequest& r) {
  nlohmann::json j = scene.json();
  applyRenderSettings(j, set, scene.path());
  nlohmann::json& render = j["render"];
  if (!render.is_object()) render = nlohmann::json::object();
  if (r.spp) render["spp"] = *r.spp;
  if (r.time) {
    render["time"] = *r.time;
    if (!r.spp) render["spp"] = 1 << 30;
  }
  if (r.seed) render["seed"] = *r.seed;
  return j;
}

// The render job of `scene`; what it refuses raises InputError naming the argument or the render
// object's setting (a keyword argument or the scene's own) that caused it.
std::unique_ptr<RenderJob> makeJob(const Scene& scene, RenderJobOptions o) {
  try {
    return std::make_unique<RenderJob>(scene, std::move(o));
  } catch (const RenderJobError& e) {
    throw InputError("kasha.render", e.setting, e.what());
  } catch (const WavelengthStrategyError& e) {
    throw InputError(scene.path, "/render/" + std::string(settingName(e.site())), e.what());
  } catch (const PpmNeeWavelengthsError& e) {
    throw InputError(scene.path, "/render/ppm/nee_wavelengths", e.what());
  } catch (const FluorescentLanesError& e) {
    throw InputError(scene.path, "/render/fluorescent_lanes", e.what());
  } catch (const std::invalid_argument& e) {  // an unknown integrator, or settings it cannot take
    throw InputError("kasha.render", "integrator", e.what());
  }
}

// A keyword argument as settings of the render object, a dict flattened to its leaves
// (bdpt={"families": "own"} is bdpt.families), so that it merges with the scene's own object as
// `--set bdpt.families=own` does.
void addSettings(const std::string& key, const py::handle& value, std::vector<RenderSetting>& set) {
  if (py::isinstance<py::dict>(value)) {
    for (const auto& [k, v] : value.cast<py::dict>()) addSettings(key + "." + py::str(k).cast<std::string>(), v, set);
    return;
  }
  set.push_back({key, toJson(value, "kasha.render", key), key});
}

py::array_t<float> binCentres(const SpectralBins& b) {
  py::array_t<float> a(b.count);
  for (int i = 0; i < b.count; ++i) a.mutable_at(i) = b.centre(i);
  return a;
}

}  // namespace

py::dict render(PyScene& pyScene, const RenderRequest& req, const py::object& interrupted) {
  std::vector<RenderSetting> set;  // the keyword arguments, keys of the render object
  for (const auto& [key, value] : req.settings) addSettings(py::str(key).cast<std::string>(), value, set);
  // Held until the render ends: edits and other renders of pyScene meanwhile load scenes of their
  // own and never free this one (py_scene.h).
  const std::shared_ptr<const Scene> scene = pyScene.load(withSettings(pyScene, set, req), req.memoryLimit);
  RenderJobOptions o;
  o.integrator = req.integrator.value_or(scene->render.integrator);
  if (!req.integrator)
    if (const std::string why = integratorNameError(o.integrator); !why.empty())
      throw InputError(scene->path, "/render/integrator", why);
  o.settings = scene->render;
  o.settings.memoryLimit = req.memoryLimit;
  for (const RenderSetting& s : set) o.setKeys.push_back(s.key);
  o.threads = req.threads;
  o.spectralBins = req.spectralBins;
  o.spectralStep = req.spectralStep;
  o.strategyDepth = req.strategyImages ? req.strategyDepth : -1;
  std::atomic<int> stop{0};
  o.stop = &stop;
  // Between passes: Python's signal handlers (a KeyboardInterrupt stops the render after this
  // pass), then the progress callback (an exception from it stops the render and is re-raised).
  std::optional<py::error_already_set> pending;
  bool keyboardInterrupt = false;
  o.progress = [&](int spp, double seconds, double total) {
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
  const std::unique_ptr<RenderJob> job = makeJob(*scene, std::move(o));
  // As on the command line, the output is checked before the first sample (core/output_file.h).
  if (!req.output.empty()) checkOutputs({{req.output, "output", ".exr", ""}});
  {
    py::gil_scoped_release release;
    job->run();
  }
  const Film& film = job->film();
  if (!req.output.empty()) writeExr(film, req.output, job->spectral());

  py::dict result;
  result["xyz"] = xyzArray(film);
  result["rgb"] = rgbArray(result["xyz"].cast<py::array_t<float>>());
  result["stats"] = fromJson(job->statistics());
  if (const SpectralFilm* spectral = job->spectral()) {
    result["spectral"] = spectralArray(*spectral);
    result["wavelengths"] = binCentres(job->bins());
    result["bin_width"] = job->bins().step;
  }
  if (const bidir::StrategyImages* strategies = job->strategies()) {
    py::dict images;
    for (const auto& [name, img] : strategies->images()) {
      images[py::str(name)] = xyzArray(img->weighted);
      images[py::str(name + "_unweighted")] = xyzArray(img->unweighted);
    }
    result["strategies"] = images;
  }
  if (pending) {
    if (!keyboardInterrupt) throw std::move(*pending);
    py::object e = interrupted(py::str("render interrupted after " + std::to_string(job->stats().spp) +
                                       " samples per pixel; the partial result is in .result"));
    e.attr("result") = result;
    PyErr_SetObject(interrupted.ptr(), e.ptr());
    throw py::error_already_set();
  }
  return result;
}

}  // namespace kasha::python
