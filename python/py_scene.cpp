#include "python/py_scene.h"

#include <pybind11/numpy.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/error.h"
#include "scene/scene_loader.h"
#include "core/spectrum_json.h"

namespace py = pybind11;

namespace kasha::python {

nlohmann::json toJson(const py::handle& value) {
  py::object v = py::reinterpret_borrow<py::object>(value);
  if (py::hasattr(v, "tolist")) v = v.attr("tolist")();
  const std::string text = py::module_::import("json").attr("dumps")(v).cast<std::string>();
  return nlohmann::json::parse(text);
}

py::object fromJson(const nlohmann::json& value) { return py::module_::import("json").attr("loads")(value.dump()); }

PyScene PyScene::fromFile(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) throw InputError(path, "", "cannot open scene file");
  std::ifstream in(path, std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  if (!in && !in.eof()) throw InputError(path, "", "cannot read scene file");
  nlohmann::json json;
  try {
    json = nlohmann::json::parse(text.str());
  } catch (const nlohmann::json::parse_error& e) {
    throw InputError(path, "", std::string("malformed JSON: ") + e.what());
  }
  return PyScene(std::move(json), path);
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
    loaded_ = loadSceneFromString(text, path_, options);
    loadedText_ = text;
    loadedLimit_ = memoryLimit;
  }
  return *loaded_;
}

}  // namespace kasha::python
