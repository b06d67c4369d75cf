#include "python/py_scene.h"

#include <pybind11/numpy.h>

#include <filesystem>
#include <iostream>

#include "core/error.h"
#include "core/json_parse.h"
#include "core/spectrum_json.h"
#include "scene/mitsuba/mitsuba_scene.h"
#include "scene/scene_loader.h"

namespace py = pybind11;

namespace kasha::python {

nlohmann::json toJson(const py::handle& value) {
  py::object v = py::reinterpret_borrow<py::object>(value);
  if (py::hasattr(v, "tolist")) v = v.attr("tolist")();
  const std::string text = py::module_::import("json").attr("dumps")(v).cast<std::string>();
  return parseJsonStrict(text, "<python value>");  // bounded nesting, as for scene files
}

py::object fromJson(const nlohmann::json& value) { return py::module_::import("json").attr("loads")(value.dump()); }

PyScene PyScene::fromFile(const std::string& path) {
  // Read by core/input_file.h's rule (a regular file, size-capped, never blocking) and parsed
  // strictly, as `kasha render` does; a Mitsuba scene (.xml) becomes its kasha JSON translation.
  const std::string text = readSceneFile(path);
  if (!mitsuba::isMitsubaScenePath(path)) return PyScene(parseJsonStrict(text, path), path);
  mitsuba::Translation t = mitsuba::translateMitsubaScene(text, path);
  for (const std::string& n : t.notes) std::cerr << "kasha: note: " << n << "\n";
  return PyScene(std::move(t.scene), path);
}

PyScene PyScene::fromDict(const py::dict& scene, const std::string& baseDir) {
  // Relative file names in the dict start from baseDir; messages call the scene "<dict>".
  return PyScene(toJson(scene), (std::filesystem::path(baseDir) / "<dict>").string());
}

py::object PyScene::get(const std::string& pointer) const {
  try {
    return fromJson(json_.at(nlohmann::json::json_pointer(pointer)));
  } catch (const nlohmann::json::exception& e) {
    throw py::key_error(path_ + ": " + pointer + ": " + e.what());
  }
}

void PyScene::set(const std::string& pointer, const py::object& value) {
  try {
    json_[nlohmann::json::json_pointer(pointer)] = toJson(value);
  } catch (const nlohmann::json::exception& e) {
    throw py::key_error(path_ + ": " + pointer + ": " + e.what());
  }
}

py::tuple PyScene::spectrum(const std::string& pointer) const {
  nlohmann::json value;
  try {
    value = json_.at(nlohmann::json::json_pointer(pointer));
  } catch (const nlohmann::json::exception& e) {
    throw py::key_error(path_ + ": " + pointer + ": " + e.what());
  }
  // Named spectra are resolved from the scene's "spectra" section, as the loader does (at most
  // 64 levels deep: the loader refuses longer chains and cycles).
  std::map<std::string, Spectrum> resolved;
  SpectrumContext ctx(path_, std::filesystem::path(path_).parent_path().string(), &resolved);
  int depth = 0;
  ctx.resolveName = [&](const std::string& name, const std::string&) -> const Spectrum* {
    const auto named = json_.find("spectra");
    if (named == json_.end() || !named->contains(name) || ++depth > 64) return nullptr;
    const auto it = resolved.emplace(name, parseSpectrum((*named)[name], ctx, "/spectra/" + name)).first;
    --depth;
    return &it->second;
  };
  const Spectrum s = parseSpectrum(value, ctx, pointer);
  return py::make_tuple(py::array_t<float>(py::ssize_t(s.lambdas().size()), s.lambdas().data()),
                        py::array_t<float>(py::ssize_t(s.values().size()), s.values().data()));
}

const Scene& PyScene::load(const nlohmann::json& json, uint64_t memoryLimit) {
  const std::string text = json.dump();
  if (!loaded_ || text != loadedText_ || memoryLimit != loadedLimit_) {
    SceneLoadOptions options;
    options.memoryLimit = memoryLimit;
    loaded_.reset();
    loaded_ = loadSceneFromJson(json, path_, options);
    loadedText_ = text;
    loadedLimit_ = memoryLimit;
  }
  return *loaded_;
}

}  // namespace kasha::python
