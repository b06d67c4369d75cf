#pragma once
// Settings of a scene's render object given outside the scene file: `kasha render --set KEY=VALUE`
// and the keyword arguments of Python's kasha.render (docs/cli.md, docs/python.md). They are
// written into the scene's JSON before it is loaded, so the scene loader checks them in its one
// place, exactly as if the file had them (docs/scene-format.md, "Render settings").
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace kasha {

struct RenderSetting {
  std::string key;  // a path in the render object, its levels joined by '.': "ppm.alpha", "vcm_paths"
  nlohmann::json value;
  std::string text;  // as the user gave it ("ppm.alpha=0.7"), for messages
};

// "KEY=VALUE": VALUE is JSON if it parses as JSON, else a string ("ppm.direct=photons").
// Throws std::invalid_argument without '=', with an empty level in KEY, or for JSON a scene file
// may not hold (a key twice in an object, nesting deeper than kMaxJsonDepth).
RenderSetting parseRenderSetting(const std::string& text);

// The JSON pointer of a key in the scene: "ppm.alpha" → "/render/ppm/alpha".
std::string renderSettingPointer(const std::string& key);

// Writes each setting into `scene`'s render object, in order, creating the objects on its path.
// Throws InputError(path, the setting's pointer, ...) where a level on the way is not an object.
void applyRenderSettings(nlohmann::json& scene, const std::vector<RenderSetting>& settings, const std::string& path);

// The setting of `settings` that set the field at JSON pointer `pointer` (it or an object around
// it), or nullptr: an error the loader found there is that setting's.
const RenderSetting* settingAt(const std::vector<RenderSetting>& settings, const std::string& pointer);

}  // namespace kasha
