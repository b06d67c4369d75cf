#pragma once
// Mitsuba 3 XML scenes (docs/mitsuba-import.md): translated into kasha's scene JSON and loaded by
// the JSON loader, so an XML scene becomes exactly the Scene its JSON translation would.
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "scene/scene_loader.h"

namespace kasha::mitsuba {

struct Translation {
  nlohmann::json scene;            // kasha scene JSON
  std::vector<std::string> notes;  // "file:line: plugin: what was approximated"
};

// Translates the Mitsuba XML `text` of the file `path`, with `parameters` given for its `$name`s
// (before its <default>s) and `searchPaths` searched for files after its own (SceneLoadOptions).
// Malformed XML and unsupported plugins or properties are InputErrors naming the file, the line and
// the plugin.
Translation translateMitsubaScene(const std::string& text, const std::string& path,
                                  const std::map<std::string, std::string>& parameters = {},
                                  const std::vector<std::string>& searchPaths = {});

// Translates and loads; prints each approximation to options.notes as "kasha: note: ...". Errors the
// JSON loader finds in the translation are reported at the XML element they came from.
std::unique_ptr<Scene> loadMitsubaScene(const std::string& text, const std::string& path, const SceneLoadOptions& options);

// Whether `path` names a Mitsuba scene (ends in .xml).
bool isMitsubaScenePath(const std::string& path);
// Whether `name` can be a `$name` parameter set from outside (`kasha render -D`, Python's
// defaults=): letters, digits and '_', not empty.
bool isParameterName(const std::string& name);
// Why `dir` cannot be a further search path (SceneLoadOptions::searchPaths) of the scene file
// `scenePath`, or "": the scene is not a Mitsuba scene, or `dir` is not a directory.
std::string searchPathProblem(const std::string& scenePath, const std::string& dir);

}  // namespace kasha::mitsuba
