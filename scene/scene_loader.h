#pragma once
// Loading scenes from JSON (the format is documented in docs/scene-format.md). Every problem is an
// InputError naming the file, the JSON pointer and the reason.
#include <memory>
#include <string>

#include "scene/scene.h"

namespace kasha {

struct SceneLoadOptions {
  // A mesh whose estimated memory (about 6 times its file size) exceeds this is refused before it
  // is read (a MemoryLimitError naming the file).
  uint64_t memoryLimit = kDefaultMemoryLimit;
};

std::unique_ptr<Scene> loadScene(const std::string& path, const SceneLoadOptions& options = {});
// Same, from JSON text; `path` names it in messages and anchors relative file names.
std::unique_ptr<Scene> loadSceneFromString(const std::string& text, const std::string& path,
                                           const SceneLoadOptions& options = {});

}  // namespace kasha
