#include "python/py_scene.h"

#include <pybind11/numpy.h>

#include <cstdint>
#include <filesystem>
#include <iostream>
#include <string>
#include <vector>

#include "core/error.h"
#include "core/json_parse.h"
#include "core/spectrum_json.h"
#include "scene/mitsuba/mitsuba_scene.h"
#include "scene/scene_loader.h"

namespace py = pybind11;

namespace kasha::python {

nlohmann::json toJson(const py::handle& value, const std::string& where, const std::string& field) {
  // numpy arrays and scalars, anywhere in the value, become lists and numbers; NaN and infinity
  // are refused (allow_nan=False) rather than written as the NaN JSON does not have.
  const py::cpp_function plain([](const py::handle& o) -> py::object {
    if (py::hasattr(o, "tolist")) return o.attr("tolist")();
    throw py::type_error("an object of type " + py::str(py::type::handle_of(o).attr("__name__")).cast<std::string>() +
                         " is not JSON");
  });
  std::string text;
  try {
    text = py::module_::import("json")
               .attr("dumps")(value, py::arg("allow_nan") = false, py::arg("default") = plain)
               .cast<std::string>();
  } catch (const py::error_already_set& e) {
    throw InputError(where, field, "cannot be written as JSON: " + py::str(e.value()).cast<std::string>());
  }
  return parseJsonStrict(text, field.empty() ? where : where + ": " + field);  // bounded nesting, as for scene files
}

py::object fromJson(const nlohmann::json& value) { return py::module_::import("json").attr("loads")(value.dump()); }

namespace {

// Refuses (InputError) a pointer that would make `json[p] = v` extend a list by more than one
// element: nlohmann's operator[] fills the gap with nulls, a list made up of them for
// "/shapes/7" where /shapes was empty, and gigabytes of them for "/shapes/99999999999". A token
// under a list, or under a value the assignment creates that it makes a list (a null or a missing
// key followed by a digit token), must be "-" or an index no larger than the list's size.
void requireWithinLists(const nlohmann::json& json, nlohmann::json::json_pointer p, const std::string& where,
                        const std::string& pointer) {
  std::vector<std::string> tokens;
  for (; !p.empty(); p.pop_back()) tokens.push_back(p.back());
  const nlohmann::json* node = &json;  // nullptr: a value the assignment creates
  for (auto t = tokens.rbegin(); t != tokens.rend(); ++t) {
    const bool digits = !t->empty() && t->find_first_not_of("0123456789") == std::string::npos;
    const bool created = !node || node->is_null();
    if (!created && !node->is_array() && !node->is_object()) return;  // nlohmann refuses the step
    if (created ? !(digits || *t == "-") : node->is_object()) {
      if (created) node = nullptr;
      else if (const auto it = node->find(*t); it != node->end()) node = &*it;
      else node = nullptr;
      continue;
    }
    const size_t size = created ? 0 : node->size();
    if (*t == "-" || !digits) {  // "-" appends; nlohmann refuses a token that is not an index
      node = nullptr;
      continue;
    }
    const size_t index = t->size() > 18 ? SIZE_MAX : std::stoull(*t);
    if (index > size)
      throw InputError(where, pointer, "index " + *t + " is past the end of a list of " + std::to_string(size) +
                                           " (index " + std::to_string(size) + " or '-' appends one)");
    node = index < size ? &(*node)[index] : nullptr;
  }
}

}  // namespace

PyScene PyScene::fromFile(const std::string& path, const std::map<std::string, std::string>& defaults,
                          const std::vector<std::string>& searchPaths) {
  // Read by core/input_file.h's rule (a regular file, size-capped, never blocking) and parsed
  // strictly, as `kasha render` does; a Mitsuba scene (.xml) becomes its kasha JSON translation.
  for (const auto& [name, value] : defaults) {
    if (!mitsuba::isMitsubaScenePath(path))
      throw InputError("kasha.Scene", "defaults", "sets parameters of a Mitsuba XML scene, not of " + path);
    if (!mitsuba::isParameterName(name))
      throw InputError("kasha.Scene", "defaults", "'" + printable(name) + "' is not a parameter name (letters, digits and '_')");
  }
  for (const std::string& dir : searchPaths)
    if (const std::string problem = mitsuba::searchPathProblem(path, dir); !problem.empty())
      throw InputError("kasha.Scene", "search_paths", printable(dir) + ": " + problem);
  const std::string text = readSceneFile(path);
  if (!mitsuba::isMitsubaScenePath(path)) return PyScene(parseJsonStrict(text, path), path);
  mitsuba::Translation t = mitsuba::translateMitsubaScene(text, path, defaults, searchPaths);
  for (const std::string& n : t.notes) std::cerr << "kasha: note: " << n << "\n";
  return PyScene(std::move(t.scene), path);
}

PyScene PyScene::fromDict(const py::dict& scene, const std::string& baseDir) {
  // Relative file names in the dict start from baseDir; messages call the scene "<dict>".
  const std::string path = (std::filesystem::path(baseDir) / "<dict>").string();
  return PyScene(toJson(scene, path, ""), path);
}

py::object PyScene::get(const std::string& pointer) const {
  try {
    return fromJson(json_.at(nlohmann::json::json_pointer(pointer)));
  } catch (const nlohmann::json::exception& e) {
    throw py::key_error(path_ + ": " + pointer + ": " + e.what());
  }
}

void PyScene::set(const std::string& pointer, const py::object& value) {
  nlohmann::json v = toJson(value, path_, pointer);
  try {
    const nlohmann::json::json_pointer p(pointer);
    requireWithinLists(json_, p, path_, pointer);
    json_[p] = std::move(v);
  } catch (const nlohmann::json::exception& e) {
    throw InputError(path_, pointer, e.what());
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

std::shared_ptr<const Scene> PyScene::load(const nlohmann::json& json, uint64_t memoryLimit) {
  const std::string text = json.dump();
  if (!loaded_ || text != loadedText_ || memoryLimit != loadedLimit_) {
    SceneLoadOptions options;
    options.memoryLimit = memoryLimit;
    loaded_.reset();  // freed first unless a running render still holds it
    loaded_ = loadSceneFromJson(json, path_, options);
    loadedText_ = text;
    loadedLimit_ = memoryLimit;
  }
  return loaded_;
}

}  // namespace kasha::python
