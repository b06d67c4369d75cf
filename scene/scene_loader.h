#pragma once
// Loading scenes from JSON (the format is documented in docs/scene-format.md). Every problem is an
// InputError naming the file, the JSON pointer and the reason.
#include <nlohmann/json_fwd.hpp>

#include <iostream>
#include <map>
#include <memory>
#include <string>

#include "scene/render_overrides.h"
#include "scene/scene.h"

namespace kasha {

struct SceneLoadOptions {
  // A mesh whose estimated memory (about 7 times its file size) or an image whose decoded pixels
  // exceed this is refused before it is read or decoded (an InputError naming the file).
  uint64_t memoryLimit = kDefaultMemoryLimit;
  // Where the Mitsuba importer reports its approximations, one line each; nullptr: nowhere.
  std::ostream* notes = &std::cerr;
  // Written into the render object before it is read (scene/render_overrides.h), so the loader
  // checks them as the file's own; a Mitsuba scene gets them in its JSON translation.
  std::vector<RenderSetting> renderSettings;
  // A Mitsuba scene's `$name` parameters (`kasha render -D name=value`): they win over its
  // <default>s. A JSON scene takes none.
  std::map<std::string, std::string> parameters;
  // A Mitsuba scene's further file search paths (`kasha render -a DIR`, as Mitsuba's `-a`):
  // searched, in order, after its <path>s and its own directory.
  std::vector<std::string> searchPaths;
};

// The text of a scene file (core/input_file.h: a regular file of at most kMaxJsonFileBytes).
std::string readSceneFile(const std::string& path);
// Reads and loads a scene file.
// A path ending in .xml is a Mitsuba 3 scene (scene/mitsuba/mitsuba_scene.h), anything else kasha JSON.
std::unique_ptr<Scene> loadScene(const std::string& path, const SceneLoadOptions& options = {});
// Same, from JSON text; `path` names it in messages and anchors relative file names.
std::unique_ptr<Scene> loadSceneFromString(const std::string& text, const std::string& path,
                                           const SceneLoadOptions& options = {});
// Same, from parsed JSON (the Mitsuba importer's translation).
std::unique_ptr<Scene> loadSceneFromJson(const nlohmann::json& root, const std::string& path,
                                         const SceneLoadOptions& options = {});

}  // namespace kasha
