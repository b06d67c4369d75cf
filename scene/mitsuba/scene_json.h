#pragma once
// The kasha scene JSON (docs/scene-format.md) a Mitsuba import builds, and where in the XML each
// of its parts came from, so errors the JSON loader finds later still name the XML file and line.
#include <nlohmann/json.hpp>

#include <map>
#include <string>

#include "scene/mitsuba/xml_plugin.h"

namespace kasha::mitsuba {

struct SceneJson {
  nlohmann::json root = nlohmann::json::object();
  // JSON pointer ("/shapes/3", "/materials/wall") → "file:line" and the plugin.
  std::map<std::string, std::pair<std::string, std::string>> origins;
  std::map<std::string, std::string> bsdfIds;  // XML id → material name ("" for a null BSDF: none)
  std::map<std::string, std::string> mediumIds;  // XML id → medium name in /media
  pugi::xml_node integrator;  // the <integrator>, if any (Mitsuba's default is `path`)
  // Objects declared at the top level with an id and used only where a <ref id=".."/> names them
  // (an area <emitter> for shapes, a <sampler> for the sensor), by id.
  std::map<std::string, pugi::xml_node> declared;
  // The declared object `id` if it is a <tag>, else an empty node.
  pugi::xml_node declaredAs(const std::string& id, const char* tag) const {
    const auto it = declared.find(id);
    return it != declared.end() && std::string(it->second.name()) == tag ? it->second : pugi::xml_node();
  }

  void origin(const std::string& pointer, const XmlImport& xml, pugi::xml_node n) {
    origins[pointer] = {xml.where(n), XmlImport::describe(n)};
  }
  // Adds a material under a unique name and returns the name.
  std::string addMaterial(const XmlImport& xml, pugi::xml_node bsdf, nlohmann::json material);
  // The name addMaterial gave the element `n`'s material (a nested <bsdf>, or a shape's default),
  // or null: an instanced shape's material is translated once.
  const std::string* materialOf(pugi::xml_node n) const {
    const auto it = materialNames.find(n);
    return it == materialNames.end() ? nullptr : &it->second;
  }
  std::map<pugi::xml_node, std::string> materialNames;
};

}  // namespace kasha::mitsuba
