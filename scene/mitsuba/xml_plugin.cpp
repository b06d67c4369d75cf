#include "scene/mitsuba/xml_plugin.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <map>
#include <sstream>

#include "core/input_file.h"

namespace kasha::mitsuba {

// ---- files ----------------------------------------------------------------------------------

const pugi::xml_document& XmlImport::load(std::string text, const std::string& path) {
  File& f = files_.emplace_back();
  f.path = path;
  f.text = std::move(text);
  f.lineStarts.push_back(0);
  for (size_t i = 0; i < f.text.size(); ++i)
    if (f.text[i] == '\n') f.lineStarts.push_back(i + 1);
  // parse_fragment keeps text outside the root element (pugixml drops it otherwise), to refuse it.
  const pugi::xml_parse_result r =
      f.doc.load_buffer(f.text.data(), f.text.size(), pugi::parse_default | pugi::parse_comments | pugi::parse_fragment);
  if (!r) {
    const size_t off = size_t(std::max<ptrdiff_t>(0, r.offset));
    const size_t line = size_t(std::upper_bound(f.lineStarts.begin(), f.lineStarts.end(), off) - f.lineStarts.begin());
    throw InputError(path + ":" + std::to_string(line), "", std::string("malformed XML: ") + r.description());
  }
  const pugi::xml_node root = f.doc.document_element();
  if (!root) throw InputError(path + ":1", "", "malformed XML: no root element");
  if (std::string(root.name()) != "scene")
    throw InputError(path + ":1", "", "the root element is <" + std::string(root.name()) + ">, expected <scene>");
  checkStructure(f);
  return f.doc;
}

namespace {

// Elements that hold no elements: Mitsuba's properties (a <spectrum> without a type is one) and
// the operations of a <transform>. Anything inside them would be ignored.
bool holdsNoElements(pugi::xml_node n) {
  static const std::set<std::string> tags = {"float", "integer", "boolean", "string", "point", "vector", "rgb",
                                             "blackbody", "ref", "default", "include", "path", "translate", "rotate",
                                             "scale", "matrix", "lookat"};
  const std::string tag = n.name();
  return tags.count(tag) || (tag == "spectrum" && !n.attribute("type"));
}

// pugixml's tree walk is a loop (no recursion), so any depth of input is safe to check.
struct StructureWalker : pugi::xml_tree_walker {
  pugi::xml_node tooDeep, inside;  // the first offence found
  bool for_each(pugi::xml_node& n) override {
    if (n.type() != pugi::node_element) return true;
    if (depth() > kMaxXmlDepth) tooDeep = n;
    else if (holdsNoElements(n.parent())) inside = n;
    return !tooDeep && !inside;
  }
};

}  // namespace

void XmlImport::checkStructure(const File& f) const {
  // pugixml accepts several top-level elements and text around the root; XML has one root element.
  const pugi::xml_node root = f.doc.document_element();
  for (pugi::xml_node n = f.doc.first_child(); n; n = n.next_sibling()) {
    if (n == root || (n.type() != pugi::node_element && n.type() != pugi::node_pcdata && n.type() != pugi::node_cdata))
      continue;
    const bool after = root.offset_debug() < n.offset_debug();
    throw InputError(where(n), "", n.type() == pugi::node_element ? "a second root element <" + std::string(n.name()) +
                                                                        "> after </scene> (a file holds one scene)"
                                                                  : std::string("text ") + (after ? "after </scene>" : "before <scene>"));
  }
  StructureWalker w;
  pugi::xml_node(f.doc).traverse(w);  // a handle: traverse() is not const
  if (w.tooDeep) fail(w.tooDeep, nestedDeeperThan(kMaxXmlDepth));
  if (w.inside)
    throw InputError(where(w.inside), describe(w.inside.parent()),
                     "<" + std::string(w.inside.name()) + "> inside it (a property or transform operation holds no elements)");
}

const pugi::xml_document& XmlImport::parse(const std::string& text, const std::string& path) {
  including_ = {path};
  return load(text, path);
}

const pugi::xml_document& XmlImport::include(const std::string& path, pugi::xml_node from) {
  const std::string canon = std::filesystem::weakly_canonical(path).string();
  for (const std::string& p : including_)
    if (std::filesystem::weakly_canonical(p).string() == canon) fail(from, "'" + path + "' includes itself (a cycle of <include>s)");
  std::string text;
  try {
    text = readInputFile(path, "included scene file", kMaxJsonFileBytes);  // regular files only, never blocks
  } catch (const std::runtime_error& e) {
    fail(from, e.what());
  }
  including_.push_back(path);
  return load(text, path);
}

const XmlImport::File& XmlImport::fileOf(pugi::xml_node n) const {
  const pugi::xml_node root = n.root();
  for (const File& f : files_)
    if (f.doc == root) return f;
  return files_.front();
}

std::string XmlImport::where(pugi::xml_node n) const {
  const File& f = fileOf(n);
  const size_t off = size_t(std::max<ptrdiff_t>(0, n.offset_debug()));
  const size_t line = size_t(std::upper_bound(f.lineStarts.begin(), f.lineStarts.end(), off) - f.lineStarts.begin());
  return f.path + ":" + std::to_string(line);
}

std::string XmlImport::baseDir(pugi::xml_node n) const {
  const std::string dir = std::filesystem::path(fileOf(n).path).parent_path().string();
  return dir.empty() ? "." : dir;
}

std::string XmlImport::resolve(pugi::xml_node n, const std::string& rel) const {
  // Absolute, so that the JSON loader (which resolves against the top-level file) keeps it.
  if (!rel.empty() && rel[0] == '/') return rel;
  auto existing = [&](const std::string& dir) -> std::optional<std::string> {
    const std::filesystem::path candidate = std::filesystem::absolute(std::filesystem::path(dir) / rel).lexically_normal();
    std::error_code error;
    if (std::filesystem::exists(candidate, error)) return candidate.string();
    return std::nullopt;
  };
  for (auto dir = searchPaths_.rbegin(); dir != searchPaths_.rend(); ++dir)
    if (std::optional<std::string> found = existing(*dir)) return *found;
  if (std::optional<std::string> found = existing(baseDir(n))) return *found;
  // Mitsuba's file resolver also holds the top-level scene's directory (an included file may name
  // files relative to the scene that includes it).
  const std::string sceneDir = std::filesystem::path(files_.front().path).parent_path().string();
  if (std::optional<std::string> found = existing(sceneDir.empty() ? "." : sceneDir)) return *found;
  for (const std::string& dir : fallbackPaths_)
    if (std::optional<std::string> found = existing(dir)) return *found;
  return std::filesystem::absolute(baseDir(n) + "/" + rel).lexically_normal().string();
}

void XmlImport::addFallbackPath(const std::string& dir) {
  fallbackPaths_.push_back(std::filesystem::absolute(dir).lexically_normal().string());
}

void XmlImport::addSearchPath(pugi::xml_node n, const std::string& dir) {
  // Mitsuba 3 (<path>): relative to the file that holds it, else through the file resolver.
  std::string path = std::filesystem::absolute(baseDir(n) + "/" + dir).lexically_normal().string();
  std::error_code error;
  if (dir.empty() || dir[0] == '/' || !std::filesystem::is_directory(path, error)) path = resolve(n, dir);
  if (!std::filesystem::is_directory(path, error)) fail(n, "path '" + dir + "' is not a directory (" + path + ")");
  searchPaths_.push_back(path);
}

std::string XmlImport::label(pugi::xml_node n) const {
  const std::string w = where(n);
  const std::string type = n.attribute("type") ? n.attribute("type").value() : n.name();
  return type + "@" + std::filesystem::path(w).filename().string();
}

// ---- attributes and parameters ------------------------------------------------------------

std::optional<std::string> XmlImport::optionalAttribute(pugi::xml_node n, const char* name) const {
  const pugi::xml_attribute a = n.attribute(name);
  if (!a) return std::nullopt;
  // Mitsuba's `$name` parameters: the longest run of name characters after '$'.
  std::string in = a.value(), out;
  for (size_t i = 0; i < in.size(); ++i) {
    if (in[i] != '$') {
      out += in[i];
      continue;
    }
    size_t j = i + 1;
    while (j < in.size() && (std::isalnum(static_cast<unsigned char>(in[j])) || in[j] == '_')) ++j;
    const std::string key = in.substr(i + 1, j - i - 1);
    const auto it = params_.find(key);
    if (key.empty() || it == params_.end())
      fail(n, std::string("attribute '") + name + "': parameter '$" + key + "' has no <default> value");
    out += it->second;
    i = j - 1;
  }
  return out;
}

std::string XmlImport::attribute(pugi::xml_node n, const char* name) const {
  std::optional<std::string> v = optionalAttribute(n, name);
  if (!v) fail(n, std::string("missing attribute '") + name + "'");
  return *v;
}

std::string XmlImport::describe(pugi::xml_node n) {
  std::string s = n.name();
  if (const pugi::xml_attribute t = n.attribute("type")) s += std::string(" '") + t.value() + "'";
  else if (const pugi::xml_attribute nm = n.attribute("name")) s += std::string(" '") + nm.value() + "'";
  return s;
}

void XmlImport::claimId(pugi::xml_node n) {
  const std::string id = attribute(n, "id");
  const auto [it, added] = ids_.emplace(std::pair<std::string, std::string>(n.name(), id), n);
  if (!added && it->second != n)
    fail(n, "duplicate id '" + id + "' (the <" + it->second.name() + "> at " + where(it->second) + " has it)");
}

pugi::xml_node XmlImport::declared(const std::string& tag, const std::string& id) const {
  const auto it = ids_.find({tag, id});
  return it == ids_.end() ? pugi::xml_node() : it->second;
}

void XmlImport::fail(pugi::xml_node n, const std::string& reason) const { throw InputError(where(n), describe(n), reason); }

void XmlImport::note(pugi::xml_node n, const std::string& what) {
  std::string line = printable(where(n) + ": " + describe(n) + ": " + what);
  // Once each: an instanced shape is read once per instance.
  if (std::find(notes_.begin(), notes_.end(), line) == notes_.end()) notes_.push_back(std::move(line));
}

std::optional<std::vector<float>> parseNumbers(const std::string& text) {
  std::vector<float> out;
  const char* p = text.data();
  const char* end = p + text.size();
  for (;;) {
    while (p < end && (std::isspace(static_cast<unsigned char>(*p)) || *p == ',')) ++p;
    if (p == end) break;
    float v = 0.0f;
    if (*p == '+' && ++p < end && (*p == '-' || *p == '+')) return std::nullopt;  // from_chars takes no '+'
    const auto [q, ec] = std::from_chars(p, end, v);
    if (ec != std::errc() || !std::isfinite(v)) return std::nullopt;
    if (q < end && !std::isspace(static_cast<unsigned char>(*q)) && *q != ',') return std::nullopt;
    out.push_back(v);
    p = q;
  }
  return out;
}

// ---- plugins --------------------------------------------------------------------------------

Plugin::Plugin(XmlImport& xml, pugi::xml_node node) : xml_(xml), node_(node) {
  if (node.attribute("type")) type_ = xml.attribute(node, "type");
  if (node.attribute("id")) xml.claimId(node);
  // Plugins of what kasha does not render at all (its scope: docs/mitsuba-import.md), said as such.
  static const std::map<std::pair<std::string, std::string>, const char*> kOutOfScope = {
      {{"bsdf", "polarizer"}, "polarisation"},     {{"bsdf", "pplastic"}, "polarisation"},
      {{"bsdf", "measured_polarized"}, "polarisation"}, {{"integrator", "stokes"}, "polarisation"},
      {{"bsdf", "hair"}, "hair"},                  {{"shape", "bsplinecurve"}, "curves"},
      {{"shape", "linearcurve"}, "curves"},        {{"shape", "sdfgrid"}, "signed distance fields"}};
  const auto out = kOutOfScope.find({node.name(), type_});
  if (out != kOutOfScope.end()) fail(std::string("outside kasha's scope (") + out->second + ")");
}

bool Plugin::has(const std::string& name) const {
  for (pugi::xml_node c : node_.children())
    if (c.type() == pugi::node_element && name == c.attribute("name").value()) return true;
  return false;
}

pugi::xml_node Plugin::property(const std::string& name) {
  pugi::xml_node found;
  for (pugi::xml_node c : node_.children()) {
    if (c.type() != pugi::node_element || name != c.attribute("name").value()) continue;
    if (found) xml_.fail(c, "property '" + name + "' is given twice (also at " + xml_.where(found) + ")");
    found = c;
  }
  if (found) used_.insert(found.internal_object());
  return found;
}

float Plugin::numberOf(pugi::xml_node p) {
  const std::string tag = p.name();
  if (tag != "float" && tag != "integer")
    fail(p, "expected <float> or <integer>, got <" + tag + ">");
  const auto v = parseNumbers(xml_.attribute(p, "value"));
  if (!v || v->size() != 1) fail(p, "value '" + xml_.attribute(p, "value") + "' is not a finite number");
  return v->front();
}

float Plugin::number(const std::string& name, float fallback) {
  const pugi::xml_node p = property(name);
  return p ? numberOf(p) : fallback;
}

float Plugin::number(const std::string& name) {
  const pugi::xml_node p = property(name);
  if (!p) fail("missing property '" + name + "'");
  return numberOf(p);
}

int Plugin::integer(const std::string& name, int fallback) {
  const pugi::xml_node p = property(name);
  if (!p) return fallback;
  const std::string text = xml_.attribute(p, "value");
  int v = 0;
  const auto [q, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
  if (std::string(p.name()) != "integer" || ec != std::errc() || q != text.data() + text.size())
    fail(p, "expected <integer value=\"N\">, got <" + std::string(p.name()) + " value=\"" + text + "\">");
  return v;
}

bool Plugin::boolean(const std::string& name, bool fallback) {
  const pugi::xml_node p = property(name);
  if (!p) return fallback;
  const std::string text = xml_.attribute(p, "value");
  if (std::string(p.name()) != "boolean" || (text != "true" && text != "false"))
    fail(p, "expected <boolean value=\"true|false\">");
  return text == "true";
}

std::string Plugin::string(const std::string& name, const std::string& fallback) {
  const pugi::xml_node p = property(name);
  if (!p) return fallback;
  if (std::string(p.name()) != "string") fail(p, "expected <string>");
  return xml_.attribute(p, "value");
}

std::vector<pugi::xml_node> Plugin::nested(const char* tag) {
  std::vector<pugi::xml_node> out;
  for (pugi::xml_node c : node_.children(tag)) {
    used_.insert(c.internal_object());
    out.push_back(c);
  }
  return out;
}

void Plugin::fail(pugi::xml_node at, const std::string& reason) const {
  throw InputError(xml_.where(at), XmlImport::describe(node_), reason);
}

void Plugin::finish() const {
  for (pugi::xml_node c : node_.children()) {
    if (c.type() != pugi::node_element || used_.count(c.internal_object())) continue;
    const std::string what = c.attribute("name") ? "property '" + std::string(c.attribute("name").value()) + "'"
                                                 : "<" + std::string(c.name()) + ">";
    fail(c, "unsupported " + what + " (<" + c.name() + ">) for this plugin in kasha");
  }
}

}  // namespace kasha::mitsuba
