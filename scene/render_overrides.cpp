#include "scene/render_overrides.h"

#include <stdexcept>

#include "core/error.h"
#include "core/json_parse.h"

namespace kasha {
namespace {

std::vector<std::string> levels(const std::string& key) {
  std::vector<std::string> out;
  size_t start = 0;
  for (;;) {
    const size_t dot = key.find('.', start);
    out.push_back(key.substr(start, dot == std::string::npos ? std::string::npos : dot - start));
    if (out.back().empty()) throw std::invalid_argument("'" + key + "' has an empty level (expected e.g. ppm.alpha)");
    if (dot == std::string::npos) return out;
    start = dot + 1;
  }
}

}  // namespace

RenderSetting parseRenderSetting(const std::string& text) {
  const size_t eq = text.find('=');
  if (eq == std::string::npos)
    throw std::invalid_argument("expected KEY=VALUE, KEY a setting of the scene's render object (docs/scene-format.md)");
  RenderSetting s{text.substr(0, eq), nullptr, text};
  levels(s.key);
  const std::string value = text.substr(eq + 1);
  // accept() builds nothing, so any text is safe to try; JSON is then read as strictly as a scene
  // file (core/json_parse.h: no duplicate keys, no nesting that recursive code could not take).
  if (!nlohmann::json::accept(value)) {
    s.value = value;
    return s;
  }
  try {
    s.value = parseJsonStrict(value, "");
  } catch (const InputError& e) {
    throw std::invalid_argument(e.what());
  }
  return s;
}

std::string renderSettingPointer(const std::string& key) {
  std::string pointer = "/render";
  for (const std::string& level : levels(key)) pointer += "/" + level;
  return pointer;
}

void applyRenderSettings(nlohmann::json& scene, const std::vector<RenderSetting>& settings, const std::string& path) {
  for (const RenderSetting& s : settings) {
    nlohmann::json* at = &scene;
    std::string pointer;
    const std::vector<std::string> keys = levels(s.key);
    for (size_t i = 0; i <= keys.size(); ++i) {
      if (at->is_null()) *at = nlohmann::json::object();
      if (!at->is_object())
        throw InputError(path, renderSettingPointer(s.key), (pointer.empty() ? "the scene" : pointer) + " is not an object");
      const std::string& level = i == 0 ? std::string("render") : keys[i - 1];
      pointer += "/" + level;
      at = &(*at)[level];
      if (i == keys.size()) *at = s.value;
    }
  }
}

const RenderSetting* settingAt(const std::vector<RenderSetting>& settings, const std::string& pointer) {
  // The last one wins, as it does in applyRenderSettings.
  for (auto it = settings.rbegin(); it != settings.rend(); ++it) {
    const std::string p = renderSettingPointer(it->key);
    if (pointer == p || pointer.rfind(p + "/", 0) == 0) return &*it;
  }
  return nullptr;
}

}  // namespace kasha
