#pragma once
// Loading scenes from JSON (the format is documented in docs/scene-format.md). Every problem is an
// InputError naming the file, the JSON pointer and the reason.
#include <memory>
#include <string>

#include "core/scene.h"

namespace kasha {

std::unique_ptr<Scene> loadScene(const std::string& path);
// Same, from JSON text; `path` names it in messages and anchors relative file names.
std::unique_ptr<Scene> loadSceneFromString(const std::string& text, const std::string& path);

}  // namespace kasha
