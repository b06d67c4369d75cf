// The Python module `kasha` (pybind11): scenes from files or dicts, renders to numpy arrays,
// metrics on arrays, spectral OpenEXR reading. Built by the project's CMake into build/python/
// (docs/python.md). Errors are Python exceptions carrying kasha's message (file, field, reason).
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <filesystem>

#include "core/error.h"
#include "core/image_input.h"
#include "core/memory_budget.h"
#include "core/spectral_exr.h"
#include "integrators/comparison.h"
#include "integrators/integrator_factory.h"
#include "integrators/render_numbers.h"
#include "python/py_arguments.h"
#include "python/py_arrays.h"
#include "python/py_render.h"
#include "python/py_scene.h"

namespace py = pybind11;
using kasha::python::PyScene;

namespace {

py::dict readExr(const py::object& path, const py::object& memoryLimit) {
  py::dict out;
  const kasha::ExrImage img = kasha::readExrImage(kasha::python::filePath(path, {"kasha.read_exr", "path"}),
                                                 kasha::python::byteSize(memoryLimit, {"kasha.read_exr", "memory_limit"}));
  out["xyz"] = kasha::python::xyzArray(img.xyz);
  if (!img.spectral.wavelengths.empty()) {
    const kasha::SpectralImage& s = img.spectral;
    out["spectral"] = kasha::python::spectralArray(s);
    out["wavelengths"] = py::array_t<float>(py::ssize_t(s.wavelengths.size()), s.wavelengths.data());
  }
  return out;
}

// The image and the reference of kasha.metrics or kasha.error_map (`function`), checked as
// `kasha metrics` checks its files: the same size, at least one pixel, every value finite.
std::pair<kasha::XyzImage, kasha::XyzImage> imagePair(const py::object& image, const py::object& reference,
                                                      const char* function) {
  kasha::XyzImage a = kasha::python::toXyzImage(image, {function, "image"});
  kasha::XyzImage r = kasha::python::toXyzImage(reference, {function, "reference"});
  if (a.width != r.width || a.height != r.height)
    throw kasha::InputError(function, "reference", "is " + std::to_string(r.height) + "x" + std::to_string(r.width) +
                                                       " pixels, the image " + std::to_string(a.height) + "x" +
                                                       std::to_string(a.width));
  return {std::move(a), std::move(r)};
}

py::array_t<float> errorMap(const py::object& image, const py::object& reference) {
  const auto [a, r] = imagePair(image, reference, "kasha.error_map");
  const std::vector<float> map = kasha::relativeErrorMap(a, r);
  py::array_t<float> out({py::ssize_t(a.height), py::ssize_t(a.width)});
  std::copy(map.begin(), map.end(), out.mutable_data());
  return out;
}

// Keyword arguments of kasha.render that RenderJobOptions takes as they are (0: none), beside the
// ones the command line shares (integrators/render_numbers.h).
constexpr kasha::NumberRule kSpectralBins{kasha::Sign::NonNegative, true, kasha::SpectralBins::kMaxBins};
constexpr kasha::NumberRule kSpectralStep{kasha::Sign::NonNegative, false};

}  // namespace

PYBIND11_MODULE(kasha, m) {
  m.doc() = "kasha: a spectral renderer for fluorescence research. Load a scene (kasha.Scene), render it "
            "(kasha.render) to numpy arrays, compare images (kasha.metrics, kasha.error_map), read spectral "
            "OpenEXR files (kasha.read_exr).";
  m.attr("__version__") = "0.1.0";
  py::register_exception<kasha::InputError>(m, "InputError", PyExc_ValueError);
  py::register_exception<kasha::MemoryLimitError>(m, "MemoryLimitError", PyExc_MemoryError);
  // Raised by a render stopped with Ctrl-C; its `result` holds the image of the passes done.
  static py::exception<std::runtime_error> interrupted(m, "RenderInterrupted", PyExc_KeyboardInterrupt);
  m.attr("RenderInterrupted").attr("__doc__") =
      "KeyboardInterrupt raised by kasha.render after Ctrl-C, once the current pass has finished; "
      "`.result` is the partial result (every pixel has the same number of samples).";

  py::class_<PyScene>(m, "Scene", "A scene in kasha's JSON format (docs/scene-format.md), editable before each render.")
      .def(py::init([](const py::object& path, const py::object& defaults, const py::object& searchPaths) {
             std::map<std::string, std::string> parameters;
             if (!defaults.is_none()) {
               if (!py::isinstance<py::dict>(defaults)) kasha::python::refuseType({"kasha.Scene", "defaults"}, "a dict or None", defaults);
               for (const auto& [name, value] : defaults.cast<py::dict>()) {
                 if (!py::isinstance<py::str>(name)) kasha::python::refuseType({"kasha.Scene", "defaults"}, "a dict with str keys", name);
                 if (!py::isinstance<py::str>(value) && !py::isinstance<py::int_>(value) && !py::isinstance<py::float_>(value))
                   kasha::python::refuseType({"kasha.Scene", "defaults"}, "str, int or float values", value);
                 const bool isBool = py::isinstance<py::bool_>(value);
                 parameters[name.cast<std::string>()] =
                     isBool ? (value.cast<bool>() ? "true" : "false") : py::str(value).cast<std::string>();
               }
             }
             std::vector<std::string> dirs;
             if (!searchPaths.is_none()) {
               if (!py::isinstance<py::list>(searchPaths)) kasha::python::refuseType({"kasha.Scene", "search_paths"}, "a list or None", searchPaths);
               for (const py::handle dir : searchPaths.cast<py::list>())
                 dirs.push_back(kasha::python::filePath(dir, {"kasha.Scene", "search_paths"}));
             }
             return PyScene::fromFile(kasha::python::filePath(path, {"kasha.Scene", "path"}), parameters, dirs);
           }),
           py::arg("path"), py::arg("defaults") = py::none(), py::arg("search_paths") = py::none(),
           "Loads the scene file at `path` (JSON, or Mitsuba 3 XML translated). `defaults` sets a Mitsuba scene's "
           "$name parameters, e.g. defaults={'spp': 64} (as `kasha render -D spp=64`); `search_paths`, a list of "
           "directories, are searched for its files after its own (as `kasha render -a DIR`). Errors (a missing file, "
           "malformed JSON or XML) raise kasha.InputError; the scene's contents are checked when it is rendered.")
      .def_static(
          "from_dict",
          [](const py::object& scene, const py::object& baseDir) {
            if (!py::isinstance<py::dict>(scene)) kasha::python::refuseType({"Scene.from_dict", "scene"}, "a dict", scene);
            return PyScene::fromDict(scene.cast<py::dict>(), kasha::python::filePath(baseDir, {"Scene.from_dict", "base_dir"}));
          },
          py::arg("scene"), py::arg("base_dir") = ".",
                  "A scene from a dict in the JSON scene format; relative file names start from `base_dir`.")
      .def(
          "get", [](const PyScene& s, const py::object& pointer) { return s.get(kasha::python::text(pointer, {"Scene.get", "pointer"})); },
          py::arg("pointer"),
           "The value at a JSON pointer, e.g. scene.get('/materials/dye/c'); KeyError if there is none.")
      .def(
          "set",
          [](PyScene& s, const py::object& pointer, const py::object& value) {
            s.set(kasha::python::text(pointer, {"Scene.set", "pointer"}), value);
          },
          py::arg("pointer"), py::arg("value"),
          "Sets the value at a JSON pointer, e.g. scene.set('/materials/dye/c', 0.5) or "
          "scene.set('/render/sensor_sampling', 'uniform'); a list grows by one element at its end (its index or "
          "'-'). Checked (and the scene reloaded) at the next render; renders already running are not affected. "
          "An index past a list's end, a malformed pointer or a value that is not JSON (NaN) raise kasha.InputError.")
      .def(
          "set_spectrum",
          [](PyScene& s, const py::object& pointer, const py::object& wavelengths, const py::object& values) {
            py::dict t;
            t["type"] = "tabulated";
            t["wavelengths"] = wavelengths;
            t["values"] = values;
            s.set(kasha::python::text(pointer, {"Scene.set_spectrum", "pointer"}), t);
          },
          py::arg("pointer"), py::arg("wavelengths"), py::arg("values"),
          "Sets a spectrum (e.g. '/materials/dye/absorption') to a table of (wavelength in nm, value).")
      .def(
          "spectrum",
          [](const PyScene& s, const py::object& pointer) { return s.spectrum(kasha::python::text(pointer, {"Scene.spectrum", "pointer"})); },
          py::arg("pointer"),
           "The spectrum at a JSON pointer (a number, a name, a table, a Gaussian, ...) as (wavelengths, values): "
           "the knots of the piecewise-linear function kasha renders with.")
      .def(
          "set_material",
          [](PyScene& s, const py::object& material, const py::kwargs& params) {
            const std::string name = kasha::python::text(material, {"Scene.set_material", "name"});
            if (!s.json().contains("materials") || !s.json()["materials"].contains(name))
              throw kasha::InputError(s.path(), "/materials/" + name, "no such material");
            for (const auto& [key, value] : params) s.set("/materials/" + name + "/" + py::str(key).cast<std::string>(),
                                                         py::reinterpret_borrow<py::object>(value));
          },
          py::arg("name"),
          "Sets parameters of a material, e.g. scene.set_material('dye', c=0.5, Q=0.8); spectra as numbers, "
          "names or {'type': 'tabulated', ...} dicts.")
      .def_property_readonly("materials",
                             [](const PyScene& s) {
                               std::vector<std::string> names;
                               if (s.json().contains("materials"))
                                 for (auto it = s.json()["materials"].begin(); it != s.json()["materials"].end(); ++it)
                                   names.push_back(it.key());
                               return names;
                             },
                             "The names of the scene's materials.")
      .def("to_dict", [](const PyScene& s) { return kasha::python::fromJson(s.json()); },
           "The scene's JSON as a dict (a copy).")
      .def_property_readonly("path", &PyScene::path, "The file the scene came from (or '<base_dir>/<dict>').");

  m.def(
      "render",
      [](const py::object& scene, const py::object& integrator, const py::object& spp, const py::object& time,
         const py::object& seed, const py::object& threads, const py::object& spectralBins,
         const py::object& spectralStep, const py::object& strategyImages, const py::object& strategyDepth,
         const py::object& memoryLimit, const py::object& progress, const py::object& output,
         const py::kwargs& settings) {
        namespace rn = kasha::render_numbers;
        using kasha::python::integer, kasha::python::number;
        const auto arg = [](const char* name) { return kasha::python::Argument{"kasha.render", name}; };
        if (!py::isinstance<PyScene>(scene)) kasha::python::refuseType(arg("scene"), "a kasha.Scene", scene);
        kasha::python::RenderRequest r;
        if (!integrator.is_none()) r.integrator = kasha::python::text(integrator, arg("integrator"));
        if (!spp.is_none()) r.spp = integer(spp, arg("spp"), rn::kSpp);
        if (!time.is_none()) r.time = number(time, arg("time"), rn::kTime);
        if (!seed.is_none()) r.seed = integer(seed, arg("seed"), rn::kSeed);
        r.threads = integer(threads, arg("threads"), rn::kThreads);
        r.spectralBins = integer(spectralBins, arg("spectral_bins"), kSpectralBins);
        r.spectralStep = number(spectralStep, arg("spectral_step"), kSpectralStep);
        r.strategyImages = kasha::python::flag(strategyImages, arg("strategy_images"));
        r.strategyDepth = integer(strategyDepth, arg("strategy_depth"), rn::kStrategyDepth);
        r.memoryLimit = kasha::python::byteSize(memoryLimit, arg("memory_limit"));
        if (!progress.is_none() && !PyCallable_Check(progress.ptr()))
          kasha::python::refuseType(arg("progress"), "a callable or None", progress);
        r.progress = progress;
        r.output = kasha::python::filePath(output, arg("output"));
        r.settings = settings;
        return kasha::python::render(scene.cast<PyScene&>(), r, interrupted);
      },
      py::arg("scene"), py::arg("integrator") = py::none(), py::arg("spp") = py::none(), py::arg("time") = py::none(),
      py::arg("seed") = py::none(), py::arg("threads") = 0, py::arg("spectral_bins") = 0,
      py::arg("spectral_step") = 0.0f, py::arg("strategy_images") = false, py::arg("strategy_depth") = 4,
      py::arg("memory_limit") = "8G", py::arg("progress") = py::none(), py::arg("output") = "",
      "Renders `scene` with an integrator (pt, lt, bdpt, ppm, vcm, vc, bpm; bdpt-shared, bdpt-independent and "
      "bdpt-mollified stand for bdpt with render/bdpt settings; None: the scene's render/integrator, else pt) for `spp` samples per pixel and/or `time` seconds "
      "(whole passes). Further keyword arguments are keys of the scene's render object: max_depth, "
      "sensor_sampling, fluorescence_sampling, nee_sampling, light_sampling, hero_wavelengths, and the "
      "integrators' own objects bdpt, vcm, ppm as dicts merged key by key, e.g. ppm={'alpha': 0.7} "
      "(docs/scene-format.md).\n\n"
      "Returns a dict: 'xyz' and 'rgb' (linear sRGB), float32 arrays of shape (height, width, 3); 'stats' (the "
      "statistics of `kasha render`); with spectral_bins=N or spectral_step=NM, 'spectral' (height, width, N): "
      "radiance per nm averaged over each bin, 'wavelengths' (bin centres, nm) and 'bin_width'; with "
      "strategy_images=True (BDPT), 'strategies': one XYZ array per (s, t) strategy, weighted and '_unweighted'. "
      "`output` also writes an OpenEXR (with the spectral bins).\n\n"
      "The GIL is released while rendering. `progress(spp, seconds, estimated_total_seconds)` is called after "
      "every pass. Ctrl-C stops after the current pass and raises kasha.RenderInterrupted (a KeyboardInterrupt) "
      "whose `result` is the partial result. The render is of the scene as it was when it started: edits and "
      "other renders of it (other threads, the progress callback) affect only later renders.\n\n"
      "Bad scenes raise kasha.InputError with kasha's message (file, JSON pointer, reason), and so do bad "
      "arguments, by the command line's rules (NaN, infinite, negative or fractional spp, time, seed, threads, "
      "strategy_depth, ...: 'kasha.render: spp: must be positive, got -3'); memory beyond `memory_limit` raises "
      "kasha.MemoryLimitError.");

  m.def(
      "metrics",
      [](const py::object& image, const py::object& reference) {
        const auto [a, r] = imagePair(image, reference, "kasha.metrics");
        const kasha::ImageError e = kasha::compareImages(a, r);
        py::dict d;
        d["rmse"] = e.rmse;
        d["relmse"] = e.relMse;
        return d;
      },
      py::arg("image"), py::arg("reference"),
      "RMSE and relMSE (mean of (x - ref)^2 / (ref^2 + 0.01)) over X, Y, Z of every pixel of two XYZ arrays of "
      "shape (height, width, 3), as `kasha metrics` computes them. Arrays of other shapes or sizes, empty ones and "
      "non-finite values raise kasha.InputError.");
  m.def("error_map", &errorMap, py::arg("image"), py::arg("reference"),
        "Per-pixel relative squared error (height, width), averaged over X, Y, Z; its mean is metrics()['relmse'].");
  m.def("read_exr", &readExr, py::arg("path"), py::arg("memory_limit") = "8G",
        "Reads an OpenEXR: 'xyz' from its XYZ layer (or integrated from its spectral channels), and 'spectral' + "
        "'wavelengths' if it has emissive S0.<nm> channels (Fichet et al. 2021). Like `kasha metrics`, it reads "
        "regular files only and refuses images whose decoded pixels exceed `memory_limit` (kasha.InputError).");
  m.def("integrators", &kasha::integratorNames, "The integrators' names.");
}
