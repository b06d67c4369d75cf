#include "scene/mitsuba/mitsuba_scene.h"

#include <algorithm>
#include <cctype>
#include <filesystem>


#include "scene/mitsuba/xml_bsdf.h"
#include "scene/mitsuba/xml_emitter.h"
#include "scene/mitsuba/xml_medium.h"
#include "scene/mitsuba/xml_sensor.h"
#include "scene/mitsuba/xml_shape.h"

namespace kasha::mitsuba {
namespace {

using nlohmann::json;

// A file's <default>s, read before its other elements (a parameter may be used anywhere in the
// file). As in Mitsuba 3, a <default> sets a parameter only if it is not set yet, so an including
// file's defaults win over an included file's, and an included file's apply after it too.
void readDefaults(XmlImport& xml, pugi::xml_node scene) {
  for (pugi::xml_node d : scene.children("default")) {
    for (pugi::xml_attribute a : d.attributes())
      if (std::string(a.name()) != "name" && std::string(a.name()) != "value")
        xml.fail(d, std::string("unexpected attribute '") + a.name() + "'");
    xml.setDefault(xml.attribute(d, "name"), xml.attribute(d, "value"));
  }
}

// Top-level objects used only where a <ref id=".."/> names them: an area emitter belongs to the
// shapes that name it, a sampler to the sensor.
bool isDeclaration(pugi::xml_node c) {
  const std::string tag = c.name();
  return (tag == "emitter" && std::string(c.attribute("type").value()) == "area") || tag == "sampler";
}

// A file's declarations, read before its other elements (a <ref> may come before what it names).
void readDeclarations(XmlImport& xml, pugi::xml_node scene, SceneJson& out) {
  for (pugi::xml_node c : scene.children()) {
    if (c.type() != pugi::node_element || !isDeclaration(c)) continue;
    if (!c.attribute("id")) xml.fail(c, "a top-level <" + std::string(c.name()) + "> of this kind needs an id to be referred to");
    xml.claimId(c);
    const auto [it, added] = out.declared.emplace(xml.attribute(c, "id"), c);
    if (!added) xml.fail(c, "duplicate id '" + it->first + "' (the <" + it->second.name() + "> at " + xml.where(it->second) + " has it)");
  }
}

// A scene's children in order, descending into <include>d files.
void visit(XmlImport& xml, pugi::xml_node scene, SceneJson& out, int depth) {
  if (depth > kMaxIncludeDepth) xml.fail(scene, "<include>s " + nestedDeeperThan(kMaxIncludeDepth));
  readDeclarations(xml, scene, out);
  for (pugi::xml_node c : scene.children()) {
    if (c.type() != pugi::node_element) continue;
    const std::string tag = c.name();
    if (tag == "default") {
      continue;  // read before (parameters may be used anywhere)
    } else if (tag == "include") {
      const pugi::xml_document& doc = xml.include(xml.resolve(c, xml.attribute(c, "filename")), c);
      readDefaults(xml, doc.document_element());
      visit(xml, doc.document_element(), out, depth + 1);
      xml.endInclude();
    } else if (tag == "path") {
      for (const pugi::xml_attribute a : c.attributes())
        if (std::string(a.name()) != "value") xml.fail(c, std::string("unexpected attribute '") + a.name() + "'");
      xml.addSearchPath(c, xml.attribute(c, "value"));
    } else if (tag == "integrator") {
      addIntegrator(xml, c, out);
    } else if (tag == "sensor") {
      addSensor(xml, c, out);
    } else if (tag == "bsdf") {
      if (!c.attribute("id")) xml.fail(c, "a top-level <bsdf> needs an id to be referred to");
      if (isNullBsdf(xml, c)) out.bsdfIds[xml.attribute(c, "id")] = "";  // no material: a medium boundary
      else out.addMaterial(xml, c, bsdfMaterial(xml, c));
    } else if (tag == "medium") {
      if (!c.attribute("id")) xml.fail(c, "a top-level <medium> needs an id to be referred to");
      addMedium(xml, c, out);
    } else if (tag == "texture") {
      // Translated where a <ref> uses it (xml_texture.h): as a colour or as a scalar.
      if (!c.attribute("id")) xml.fail(c, "a top-level <texture> needs an id to be referred to");
      xml.claimId(c);
    } else if (tag == "shape") {
      addShape(xml, c, out);
    } else if (isDeclaration(c)) {
      continue;  // declared before
    } else if (tag == "emitter") {
      addEmitter(xml, c, out);
    } else {
      xml.fail(c, "unsupported element <" + tag + "> (kasha reads default, include, path, integrator, sensor, sampler, bsdf, texture, medium, shape, emitter)");
    }
  }
}

// "path: /shapes/3/emission: reason" from the JSON loader, at the XML element /shapes/3 came from.
[[noreturn]] void rethrowAtOrigin(const InputError& e, const std::string& path, const SceneJson& sj) {
  std::string msg = e.what();
  if (msg.rfind(path + ": ", 0) == 0) msg = msg.substr(path.size() + 2);
  const std::string pointer = msg.substr(0, msg.find(": "));
  const std::pair<std::string, std::string>* best = nullptr;
  size_t bestLen = 0;
  for (const auto& [ptr, where] : sj.origins)
    if (pointer.rfind(ptr, 0) == 0 && (pointer.size() == ptr.size() || pointer[ptr.size()] == '/') && ptr.size() > bestLen) {
      best = &where;
      bestLen = ptr.size();
    }
  if (!best) throw e;
  throw InputError(best->first, best->second, "in kasha's translation " + msg);
}

}  // namespace

std::string SceneJson::addMaterial(const XmlImport& xml, pugi::xml_node bsdf, json material) {
  // Ids are unique per kind (XmlImport::claimId), but a shape's default material is named after the
  // shape's id, which a <bsdf> may share, and an unnamed BSDF's label may repeat: later ones get #2, #3.
  const std::string id = bsdf.attribute("id") ? xml.attribute(bsdf, "id") : "";
  const std::string base = id.empty() ? xml.label(bsdf) : id;
  std::string name = base;
  for (int k = 2; root["materials"].contains(name); ++k) name = base + "#" + std::to_string(k);
  root["materials"][name] = std::move(material);
  materialNames[bsdf] = name;
  origin("/materials/" + name, xml, bsdf);
  if (!id.empty()) bsdfIds[id] = name;
  return name;
}

bool isMitsubaScenePath(const std::string& path) { return path.size() >= 4 && path.ends_with(".xml"); }

bool isParameterName(const std::string& name) {
  return !name.empty() && std::all_of(name.begin(), name.end(), [](unsigned char c) { return std::isalnum(c) || c == '_'; });
}

std::string searchPathProblem(const std::string& scenePath, const std::string& dir) {
  if (!isMitsubaScenePath(scenePath)) return "adds a search path for a Mitsuba XML scene, not for " + scenePath;
  std::error_code error;
  return std::filesystem::is_directory(dir, error) ? "" : "no such directory";
}

// Reads the scene into `out`; the notes stay in `xml`.
static void build(XmlImport& xml, SceneJson& out, const std::string& text, const std::string& path,
                  const std::map<std::string, std::string>& parameters, const std::vector<std::string>& searchPaths) {
  for (const auto& [name, value] : parameters) xml.setDefault(name, value);  // first set wins
  for (const std::string& dir : searchPaths) xml.addFallbackPath(dir);
  const pugi::xml_node scene = xml.parse(text, path).document_element();
  readDefaults(xml, scene);
  visit(xml, scene, out, 0);
  if (!out.root.contains("camera")) throw InputError(path, "", "the scene has no <sensor>");
  if (!out.root.contains("shapes")) throw InputError(path, "", "the scene has no <shape>");
  // Mitsuba 3's path (its default), direct and ptracer integrators do not handle participating
  // media (their documentation); kasha's integrators transport them.
  const std::string integrator = out.integrator ? xml.attribute(out.integrator, "type") : "path";
  if (out.root.contains("media") && (integrator == "path" || integrator == "direct" || integrator == "ptracer"))
    xml.note(out.integrator ? out.integrator : scene,
             "Mitsuba's " + integrator + " integrator" + (out.integrator ? "" : " (its default)") +
                 " ignores participating media; kasha renders them (Mitsuba's volpath would)");
}

Translation translateMitsubaScene(const std::string& text, const std::string& path,
                                  const std::map<std::string, std::string>& parameters,
                                  const std::vector<std::string>& searchPaths) {
  XmlImport xml;
  SceneJson out;
  build(xml, out, text, path, parameters, searchPaths);
  return {std::move(out.root), xml.notes()};
}

std::unique_ptr<Scene> loadMitsubaScene(const std::string& text, const std::string& path, const SceneLoadOptions& options) {
  XmlImport xml;
  SceneJson out;
  build(xml, out, text, path, options.parameters, options.searchPaths);
  if (options.notes)
    for (const std::string& n : xml.notes()) *options.notes << "kasha: note: " << n << "\n";
  try {
    return loadSceneFromJson(out.root, path, options);
  } catch (const InputError& e) {
    rethrowAtOrigin(e, path, out);
  }
}

}  // namespace kasha::mitsuba
