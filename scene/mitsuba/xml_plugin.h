#pragma once
// Reading Mitsuba 3 XML scene files (https://mitsuba.readthedocs.io, "Scene format"): the files
// of one import (the scene and its <include>s), the `$name` parameters set by <default>, and one
// plugin element at a time with strict property access. Every error names the file, the line and
// the plugin ("scene.xml:12: bsdf 'plastic': ..."), and a property nobody read is an error, never
// silently ignored.
#include <pugixml.hpp>

#include <deque>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "core/error.h"

namespace kasha::mitsuba {

// The deepest element a scene file may hold, <scene> being level 0. Real scenes nest a handful of
// levels (scene, shape, bsdf, the bsdf of a twosided, a spectrum, its properties); the readers
// recurse over nested elements (a twosided's bsdf), so the limit, checked when a file is parsed,
// bounds their stack on any input.
constexpr int kMaxXmlDepth = 64;
// The longest chain of <include>s (a file including a file ...).
constexpr int kMaxIncludeDepth = 16;

// Everything one import shares: the parsed files, the parameters and the approximation notes.
class XmlImport {
 public:
  // Parses `text` as the file `path` (the top-level scene); malformed XML, content outside the
  // root element, elements nested deeper than kMaxXmlDepth and elements inside a property or a
  // transform operation are InputErrors naming the file and line.
  const pugi::xml_document& parse(const std::string& text, const std::string& path);
  // Parses the file `path` for an <include> at `from`; a cycle of includes is an error. Call
  // endInclude() when its elements have been read (the same file may be included again later).
  const pugi::xml_document& include(const std::string& path, pugi::xml_node from);
  void endInclude() { including_.pop_back(); }

  // "file:line" of a node.
  std::string where(pugi::xml_node n) const;
  // "type@file.xml:line" (the file without its directory): a name for unnamed elements.
  std::string label(pugi::xml_node n) const;
  // The directory relative file names in `n`'s file start from.
  std::string baseDir(pugi::xml_node n) const;
  // `rel` as an absolute path: in the first of the search paths (the latest <path> first) that
  // holds it, else in n's file's directory, else in the fallback paths (Mitsuba's file resolver).
  std::string resolve(pugi::xml_node n, const std::string& rel) const;
  // <path value="dir"/>: `dir` (relative to n's file) is searched before the others.
  void addSearchPath(pugi::xml_node n, const std::string& dir);
  // A directory searched after the <path>s and the files' own directories (Mitsuba's `-a`),
  // relative to the working directory.
  void addFallbackPath(const std::string& dir);

  // An attribute with `$name` parameters substituted; a missing attribute is an error.
  std::string attribute(pugi::xml_node n, const char* name) const;
  std::optional<std::string> optionalAttribute(pugi::xml_node n, const char* name) const;
  // <default name=".." value=".."/>: sets a parameter unless it is set already.
  void setDefault(const std::string& name, const std::string& value) { params_.emplace(name, value); }
  // Records the id of an object element: a second element of the same kind (<shape>, <bsdf>, ...)
  // with the same id, in the scene or its <include>s, is an error naming both. (Mitsuba wants ids
  // unique across kinds too; kasha lets a shape and its bsdf share one, as its example scene does.)
  void claimId(pugi::xml_node n);
  // The element of kind `tag` whose id was claimed as `id` so far, or an empty node.
  pugi::xml_node declared(const std::string& tag, const std::string& id) const;

  // Records an approximation (printed to stderr by the loader).
  void note(pugi::xml_node n, const std::string& what);
  const std::vector<std::string>& notes() const { return notes_; }

  // "<tag> '<type>'" (or "<tag>") for messages.
  static std::string describe(pugi::xml_node n);
  [[noreturn]] void fail(pugi::xml_node n, const std::string& reason) const;

 private:
  struct File {
    std::string path, text;
    pugi::xml_document doc;
    std::vector<size_t> lineStarts;
  };
  const File& fileOf(pugi::xml_node n) const;
  const pugi::xml_document& load(std::string text, const std::string& path);
  void checkStructure(const File& f) const;
  std::deque<File> files_;
  std::vector<std::string> including_;  // the include chain, to detect cycles
  std::vector<std::string> searchPaths_;  // <path>s, absolute, the latest last
  std::vector<std::string> fallbackPaths_;  // addFallbackPath's, absolute, in order
  std::map<std::string, std::string> params_;
  std::map<std::pair<std::string, std::string>, pugi::xml_node> ids_;  // (tag, id) → element
  std::vector<std::string> notes_;
};

// Parses a list of numbers separated by commas and/or white space ("1, 2 3"); nullopt if any
// entry is not a finite number written out to its end ("6500K" is not one).
std::optional<std::vector<float>> parseNumbers(const std::string& text);

// One plugin element (<bsdf type="diffuse">, <shape>, ...): its named properties (<float
// name="x" value=".."/>, <spectrum name="reflectance" .../>, ...) and nested plugins, each marked
// as read; finish() rejects whatever was not read.
class Plugin {
 public:
  Plugin(XmlImport& xml, pugi::xml_node node);

  const std::string& type() const { return type_; }
  pugi::xml_node node() const { return node_; }
  XmlImport& xml() const { return xml_; }

  // The property element named `name` (any tag), or an empty node.
  pugi::xml_node property(const std::string& name);
  bool has(const std::string& name) const;
  float number(const std::string& name, float fallback);
  float number(const std::string& name);
  int integer(const std::string& name, int fallback);
  bool boolean(const std::string& name, bool fallback);
  std::string string(const std::string& name, const std::string& fallback);
  // Unnamed nested elements of a tag (<bsdf> inside <twosided>, <emitter> inside <shape>).
  std::vector<pugi::xml_node> nested(const char* tag);
  // Marks an element as read without interpreting it (for callers that read it themselves).
  void markRead(pugi::xml_node n) { used_.insert(n.internal_object()); }

  [[noreturn]] void fail(const std::string& reason) const { xml_.fail(node_, reason); }
  [[noreturn]] void fail(pugi::xml_node at, const std::string& reason) const;
  void note(const std::string& what) { xml_.note(node_, what); }
  // Throws for the first child element that was never read.
  void finish() const;

 private:
  float numberOf(pugi::xml_node p);
  XmlImport& xml_;
  pugi::xml_node node_;
  std::string type_;
  std::set<const void*> used_;
};

}  // namespace kasha::mitsuba
