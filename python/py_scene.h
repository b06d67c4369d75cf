#pragma once
// The Python module's scene (python/kasha_module.cpp): a scene's JSON text (docs/scene-format.md),
// editable from Python, and the kasha::Scene loaded from it, reloaded only when the JSON changed.
#include <pybind11/pybind11.h>

#include <map>
#include <memory>
#include <string>

#include <nlohmann/json.hpp>

#include "scene/scene.h"

namespace kasha::python {

class PyScene {
 public:
  // `path` names the scene in error messages and anchors its relative file names.
  PyScene(nlohmann::json json, std::string path) : json_(std::move(json)), path_(std::move(path)) {}
  // The scene file's JSON (a Mitsuba 3 .xml scene: its translation, docs/mitsuba-import.md); InputError
  // naming the file if it cannot be read (core/input_file.h) or parsed (core/json_parse.h).
  // `defaults` sets a Mitsuba scene's `$name` parameters (before its <default>s), as `kasha render
  // -D` does; InputError for a JSON scene or a malformed name.
  static PyScene fromFile(const std::string& path, const std::map<std::string, std::string>& defaults = {},
                          const std::vector<std::string>& searchPaths = {});
  // A dict in the scene format; relative file names start from baseDir.
  static PyScene fromDict(const pybind11::dict& scene, const std::string& baseDir);

  // The JSON value at a JSON pointer ("/materials/dye/c"), as a Python object; KeyError if absent.
  pybind11::object get(const std::string& pointer) const;
  // Sets the value at a JSON pointer (numpy arrays become lists); the next render reloads. Missing
  // objects on the way are created, a list may grow by one element at its end (its index or "-");
  // anything else raises InputError: a malformed pointer, an index past a list's end, a step into
  // a number or string, a value that is not JSON (NaN, an object).
  void set(const std::string& pointer, const pybind11::object& value);
  // The spectrum at a JSON pointer as its piecewise-linear knots (wavelengths in nm, values).
  pybind11::tuple spectrum(const std::string& pointer) const;

  // The scene's JSON as edited so far, and the name it goes by in messages.
  const nlohmann::json& json() const { return json_; }
  const std::string& path() const { return path_; }
  // The scene loaded from `json` (the scene's own JSON with the render's settings in its render
  // object); the last one is kept and reused while the text is the same. A render holds the
  // pointer until it ends: edits change only the JSON, and a render of other JSON replaces the
  // kept scene without freeing it under a render still using it (docs/python.md, "Threads").
  std::shared_ptr<const Scene> load(const nlohmann::json& json, uint64_t memoryLimit);

 private:
  nlohmann::json json_;
  std::string path_;
  std::string loadedText_;
  uint64_t loadedLimit_ = 0;
  std::shared_ptr<const Scene> loaded_;
};

// Python object ↔ JSON, through Python's json module (numpy arrays and scalars through tolist()).
// A value JSON cannot hold (NaN, infinity, an arbitrary object) raises InputError(where, field).
nlohmann::json toJson(const pybind11::handle& value, const std::string& where, const std::string& field);
pybind11::object fromJson(const nlohmann::json& value);

}  // namespace kasha::python
