#include "scene/mitsuba/xml_plugin.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <filesystem>
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
  const pugi::xml_parse_result r = f.doc.load_buffer(f.text.data(), f.text.size(), pugi::parse_default | pugi::parse_comments);
  if (!r) {
    const size_t off = size_t(std::max<ptrdiff_t>(0, r.offset));
    const size_t line = size_t(std::upper_bound(f.lineStarts.begin(), f.lineStarts.end(), off) - f.lineStarts.begin());
    throw InputError(path + ":" + std::to_string(line), "", std::string("malformed XML: ") + r.description());
  }
  const pugi::xml_node root = f.doc.document_element();
  if (std::string(root.name()) != "scene")
    throw InputError(path + ":1", "", "the root element is <" + std::string(root.name()) + ">, expected <scene>");
  return f.doc;
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
  return (!rel.empty() && rel[0] == '/') ? rel : std::filesystem::absolute(baseDir(n) + "/" + rel).lexically_normal().string();
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

void XmlImport::fail(pugi::xml_node n, const std::string& reason) const { throw InputError(where(n), describe(n), reason); }

void XmlImport::note(pugi::xml_node n, const std::string& what) {
  notes_.push_back(where(n) + ": " + describe(n) + ": " + what);
}

std::optional<std::vector<float>> parseNumbers(const std::string& text) {
  std::vector<float> out;
  const char* p = text.data();
  const char* end = p + text.size();
  for (;;) {
    while (p < end && (std::isspace(static_cast<unsigned char>(*p)) || *p == ',')) ++p;
    if (p == end) break;
    float v = 0.0f;
    if (*p == '+') ++p;  // from_chars does not take a leading '+'
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
