#include "core/ply_validation.h"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <string_view>
#include <vector>

#include "core/color.h"
#include "core/error.h"
#include "core/memory_budget.h"
#include "core/text_tokens.h"

namespace kasha {
namespace {

// A header ends within this many bytes: a PLY header is a few dozen short lines, and a bound
// keeps a file without "end_header" from being scanned whole as a header.
constexpr size_t kMaxHeaderBytes = size_t(64) << 10;

// Memory held per element while a mesh is read and rendered, the basis of the check against the
// memory limit. A vertex: assimp's position, normal, colour and texture coordinate (52 bytes) and
// kasha's position (12). A face of the least size, a triangle: assimp's face and its indices with
// their allocation (44), its triangulated copy (44), kasha's indices and corner texture
// coordinates (36) and Embree's share of the BVH (about 80). Other elements are not passed on.
constexpr uint64_t kBytesPerVertex = 64;
constexpr uint64_t kBytesPerFace = 204;

// PLY's scalar types; the first name is the one written for assimp.
struct ScalarType {
  const char* name;
  const char* alias;
  uint8_t bytes;
  bool integer, isSigned;
};
constexpr ScalarType kTypes[] = {
    {"char", "int8", 1, true, true},     {"uchar", "uint8", 1, true, false}, {"short", "int16", 2, true, true},
    {"ushort", "uint16", 2, true, false}, {"int", "int32", 4, true, true},    {"uint", "uint32", 4, true, false},
    {"float", "float32", 4, false, true}, {"double", "float64", 8, false, true}};

enum class Format { Ascii, BinaryLittleEndian, BinaryBigEndian };

struct Property {
  std::string name;
  bool list = false;
  const ScalarType* count = nullptr;  // lists only
  const ScalarType* type = nullptr;   // the value's, or a list's items'
};

struct Element {
  std::string name;
  uint64_t count = 0;
  std::vector<Property> properties;
  int indexList = -1, texcoordList = -1;  // a face's lists, by position
  // Per property: −1, or 3·(mesh attribute) + channel of the attribute it is read into.
  std::vector<int> attributeSlot;
  bool trianglesOnly = false;  // a face attribute is read: every face must be a triangle
  bool readsAttributes() const {
    return std::any_of(attributeSlot.begin(), attributeSlot.end(), [](int a) { return a >= 0; });
  }
  bool isFace() const { return name == "face"; }
  // Whether it is passed on to assimp. assimp 5.2 reads the count of an element of another name
  // from its name (as 0), so it reads that element's data as the next element's (a fuzzing
  // finding: faces of garbage indices); such elements are checked and left out.
  bool passedOn() const { return name == "vertex" || isFace(); }
};

struct Header {
  Format format = Format::Ascii;
  std::vector<Element> elements;
  size_t dataStart = 0;  // the first byte after "end_header"'s line
  int lines = 0;
};

// A token as a message shows it: quoted, at most 32 bytes, control and non-ASCII bytes as \xNN
// (so that nothing from the file reaches a terminal raw).
std::string shown(std::string_view t) {
  std::string out = "'";
  for (size_t i = 0; i < t.size() && i < 32; ++i) {
    const unsigned char c = static_cast<unsigned char>(t[i]);
    if (c >= 0x20 && c < 0x7f) {
      out += char(c);
    } else {
      char hex[8];
      std::snprintf(hex, sizeof hex, "\\x%02x", c);
      out += hex;
    }
  }
  return out + (t.size() > 32 ? "...'" : "'");
}

const ScalarType* scalarType(std::string_view name) {
  for (const ScalarType& t : kTypes)
    if (name == t.name || name == t.alias) return &t;
  return nullptr;
}

std::string plural(uint64_t n, const std::string& what) { return std::to_string(n) + " " + what + (n == 1 ? "" : "s"); }

class HeaderParser {
 public:
  HeaderParser(const std::string& bytes, const std::string& path) : bytes_(bytes), path_(path) {}

  Header parse() {
    if (bytes_.compare(0, 3, "ply") != 0 || (bytes_.size() > 3 && bytes_[3] != '\n' && bytes_[3] != '\r'))
      throw InputError(path_, "header line 1", "is not 'ply': not a PLY file");
    size_t pos = 0;
    while (true) {
      const size_t end = bytes_.find('\n', pos);
      if (end == std::string::npos || end >= kMaxHeaderBytes)
        throw InputError(path_, "header", end == std::string::npos && bytes_.size() < kMaxHeaderBytes
                                              ? "the file ends before an 'end_header' line"
                                              : "no 'end_header' line within its first 64 KiB");
      std::string_view text(bytes_.data() + pos, end - pos);
      if (!text.empty() && text.back() == '\r') text.remove_suffix(1);
      pos = end + 1;
      ++header_.lines;
      where_ = "header line " + std::to_string(header_.lines);
      const std::vector<std::string_view> t = spaceSeparatedTokens(text);
      // Names reach messages: outside comments, printable ASCII only.
      const bool comment = !t.empty() && (t[0] == "comment" || t[0] == "obj_info");
      for (const char c : text)
        if (const unsigned char b = static_cast<unsigned char>(c); (b < 0x20 && c != '\t') || b == 0x7f || (!comment && b >= 0x80))
          fail("holds the byte " + shown(std::string_view(&c, 1)) + (comment ? "" : " (names and numbers are ASCII)"));
      if (line(t)) break;
    }
    header_.dataStart = pos;
    finish();
    return header_;
  }

 private:
  [[noreturn]] void fail(const std::string& reason) const { throw InputError(path_, where_, reason); }

  // One header line; true at "end_header".
  bool line(const std::vector<std::string_view>& t) {
    if (header_.lines == 1) return false;  // "ply", checked above
    if (header_.lines == 2) {
      if (t.size() != 3 || t[0] != "format") fail("expected 'format ascii 1.0' (or binary_little_endian, binary_big_endian)");
      if (t[1] == "ascii") header_.format = Format::Ascii;
      else if (t[1] == "binary_little_endian") header_.format = Format::BinaryLittleEndian;
      else if (t[1] == "binary_big_endian") header_.format = Format::BinaryBigEndian;
      else fail("unknown format " + shown(t[1]) + " (ascii, binary_little_endian, binary_big_endian)");
      if (t[2] != "1.0") fail("unknown version " + shown(t[2]) + " (1.0)");
      return false;
    }
    if (t.empty() || t[0] == "comment" || t[0] == "obj_info") return false;  // dropped
    if (t[0] == "end_header") {
      if (t.size() != 1) fail("'end_header' is followed by " + shown(t[1]));
      return true;
    }
    if (t[0] == "element") element(t);
    else if (t[0] == "property") property(t);
    else fail("unknown keyword " + shown(t[0]) + " (element, property, comment, obj_info, end_header)");
    return false;
  }

  void element(const std::vector<std::string_view>& t) {
    if (t.size() != 3) fail("expected 'element NAME COUNT'");
    Element e;
    e.name = std::string(t[1]);
    for (const Element& other : header_.elements)
      if (other.name == e.name) fail("a second element " + shown(t[1]));
    if (e.name == "tristrips") fail("element 'tristrips' (triangle strips) is not supported: write faces");
    // assimp 5.2 takes this element for a texture's name and reads neither its count nor its data.
    if (e.name == "TextureFile") fail("element 'TextureFile' is not supported");
    const std::string_view c = t[2];
    const auto r = std::from_chars(c.data(), c.data() + c.size(), e.count);
    if (c.empty() || c[0] == '-' || c[0] == '+' || r.ec != std::errc() || r.ptr != c.data() + c.size() || e.count > UINT32_MAX)
      fail("element " + shown(t[1]) + ": count " + shown(c) + " is not an integer from 0 to 4294967295");
    header_.elements.push_back(std::move(e));
  }

  void property(const std::vector<std::string_view>& t) {
    if (header_.elements.empty()) fail("a property before the first element");
    Element& e = header_.elements.back();
    Property p;
    const bool list = t.size() >= 2 && t[1] == "list";
    if (t.size() != (list ? 5u : 3u)) fail("expected 'property TYPE NAME' or 'property list COUNT_TYPE ITEM_TYPE NAME'");
    p.list = list;
    p.name = std::string(t.back());
    if (list && !(p.count = scalarType(t[2])))
      fail("unknown type " + shown(t[2]) + " (char, uchar, short, ushort, int, uint, float, double)");
    if (list && !p.count->integer) fail("a list's count must have an integer type, not " + shown(t[2]));
    if (!(p.type = scalarType(t[list ? 3 : 1])))
      fail("unknown type " + shown(t[list ? 3 : 1]) + " (char, uchar, short, ushort, int, uint, float, double)");
    for (const Property& other : e.properties)
      if (other.name == p.name) fail("element " + shown(e.name) + " has a second property " + shown(p.name));
    e.properties.push_back(std::move(p));
  }

  // What kasha reads from the elements.
  void finish() {
    int vertex = -1, face = -1;
    for (size_t i = 0; i < header_.elements.size(); ++i) {
      Element& e = header_.elements[i];
      where_ = "element " + e.name;
      if (e.properties.empty()) fail("has no properties");
      if (e.name == "vertex") vertex = int(i);
      if (e.isFace()) face = int(i);
      for (size_t p = 0; p < e.properties.size(); ++p) {
        const Property& prop = e.properties[p];
        if (e.name == "vertex" && prop.list && (prop.name == "x" || prop.name == "y" || prop.name == "z"))
          fail("property " + prop.name + " is a list, not a number");
        if (!e.isFace()) continue;
        if (prop.name == "vertex_indices" || prop.name == "vertex_index") {
          if (!prop.list || !prop.type->integer) fail("property " + prop.name + " must be a list of integers");
          if (e.indexList >= 0) fail("has two lists of vertex indices");
          e.indexList = int(p);
        } else if (prop.name == "texcoord" && prop.list) {
          e.texcoordList = int(p);
        }
      }
    }
    where_ = "header";
    if (vertex < 0) fail("no element vertex");
    for (const char* axis : {"x", "y", "z"}) {
      bool found = false;
      for (const Property& p : header_.elements[size_t(vertex)].properties) found = found || p.name == axis;
      if (!found) throw InputError(path_, "element vertex", std::string("has no property ") + axis);
    }
    if (face < 0) fail("no element face (a mesh needs faces)");
    if (face < vertex) throw InputError(path_, "element face", "comes before element vertex");
    if (header_.elements[size_t(face)].indexList < 0)
      throw InputError(path_, "element face", "has no list property vertex_indices");
    // No faces would make assimp read the vertices as a point cloud, which kasha cannot render.
    if (header_.elements[size_t(face)].count == 0) throw InputError(path_, "element face", "declares no faces");
  }

  const std::string& bytes_;
  const std::string& path_;
  std::string where_;
  Header header_;
};

// The properties each mesh attribute is read from (ply_validation.h): sets the elements' slots
// and returns the attributes, named, with their channels and no values yet.
std::vector<MeshAttribute> resolveAttributes(Header& h, const std::vector<std::string>& names, const std::string& path) {
  std::vector<MeshAttribute> out;
  for (Element& e : h.elements) e.attributeSlot.assign(e.properties.size(), -1);
  for (const std::string& name : names) {
    const bool face = name.starts_with("face_");
    if (!face && !name.starts_with("vertex_"))
      throw InputError(path, "mesh attribute '" + name + "'", "the name must start with vertex_ or face_");
    const std::string elementName = face ? "face" : "vertex", rest = name.substr(elementName.size() + 1);
    std::vector<std::array<std::string, 3>> schemes;
    if (rest.ends_with("_color")) {
      const std::string prefix = rest.substr(0, rest.size() - 6);
      schemes.push_back({prefix + "_r", prefix + "_g", prefix + "_b"});
    }
    if (rest == "color") schemes.insert(schemes.end(), {{"r", "g", "b"}, {"red", "green", "blue"}});
    schemes.insert(schemes.end(), {{rest + "_x", rest + "_y", rest + "_z"},
                                   {rest + "_0", rest + "_1", rest + "_2"},
                                   {rest + "_1", rest + "_2", rest + "_3"}});
    Element* element = nullptr;
    for (Element& e : h.elements)
      if (e.name == elementName) element = &e;
    const auto find = [&](const std::string& prop) -> int {
      for (size_t p = 0; p < element->properties.size(); ++p)
        if (element->properties[p].name == prop && !element->properties[p].list) return int(p);
      return -1;
    };
    MeshAttribute a{name, 0, {}};
    std::array<int, 3> props{-1, -1, -1};
    for (const auto& scheme : schemes) {
      const std::array<int, 3> found{find(scheme[0]), find(scheme[1]), find(scheme[2])};
      if (found[0] < 0) continue;
      if (found[1] >= 0 && found[2] >= 0) props = found, a.channels = 3;
      else if (found[1] < 0) props = {found[0], -1, -1}, a.channels = 1;
      else continue;
      break;
    }
    if (a.channels == 0)
      throw InputError(path, "element " + elementName,
                       "has no properties for the mesh attribute '" + name + "' (" + schemes.front()[0] + ", " +
                           schemes.front()[1] + ", " + schemes.front()[2] + " or one of the other namings)");
    for (int c = 0; c < a.channels; ++c) {
      int& slot = element->attributeSlot[size_t(props[size_t(c)])];
      if (slot >= 0)
        throw InputError(path, "mesh attribute '" + name + "'", "its properties are read for another attribute too");
      slot = int(3 * out.size()) + c;
    }
    if (face) element->trianglesOnly = true;
    out.push_back(std::move(a));
  }
  return out;
}

// Where attribute values go as the data is read: value/maximum of an integer type decoded from
// sRGB (Mitsuba's normalised, gamma-flagged integers), floats as they are; each in [0, 1].
class AttributeSink {
 public:
  explicit AttributeSink(std::vector<MeshAttribute>& attributes) : attributes_(attributes) {}
  // "" if accepted, else the reason.
  std::string set(int slot, uint64_t instance, double raw, const Property& p) {
    MeshAttribute& a = attributes_[size_t(slot / 3)];
    double v = raw;
    if (p.type->integer) {
      const double max = p.type->isSigned ? double((int64_t(1) << (8 * p.type->bytes - 1)) - 1)
                                           : double((int64_t(1) << (8 * p.type->bytes)) - 1);
      v = raw / max;
      if (v >= 0.0 && v <= 1.0) v = srgbDecode(float(v));
    }
    if (!(v >= 0.0 && v <= 1.0))
      return "property " + p.name + " is " + std::to_string(v) + ", outside [0, 1] (mesh attribute " + a.name + ")";
    Vec3& value = a.values[instance];
    if (a.channels == 1) value = Vec3(float(v));
    else value[slot % 3] = float(v);
    return "";
  }

 private:
  std::vector<MeshAttribute>& attributes_;
};

// The least bytes an element's instance takes in the file: its scalars and its lists' counts (the
// lists may be empty here; a face's short list is reported as such when the data is read).
uint64_t minimumBytes(const Element& e, Format format) {
  uint64_t n = 0;
  for (const Property& p : e.properties)
    n += format == Format::Ascii ? 2 : p.list ? p.count->bytes : p.type->bytes;  // ASCII: a digit and a separator
  return n;
}

uint64_t memoryBytes(const Element& e) { return e.name == "vertex" ? kBytesPerVertex : e.isFace() ? kBytesPerFace : 0; }

// The counts against the file's size and the memory limit, before the data is read.
void checkCounts(const Header& h, uint64_t dataBytes, const std::string& path, uint64_t memoryLimit) {
  uint64_t needed = 0, memory = 0;
  std::string counts;
  for (const Element& e : h.elements) {
    needed += saturatingMul(e.count, minimumBytes(e, h.format));
    if (needed > dataBytes + (h.format == Format::Ascii ? 1 : 0))  // the last line needs no line end
      throw InputError(path, "element " + e.name,
                       std::to_string(e.count) + " declared need at least " + formatBytes(needed) +
                           " of data with the elements before them, but the file holds " + formatBytes(dataBytes) +
                           " after its header (it is truncated, or the count is wrong)");
    if (!e.passedOn()) continue;
    // A mesh attribute's first channel marks it; its values are a Vec3 each.
    const auto attributes = uint64_t(
        std::count_if(e.attributeSlot.begin(), e.attributeSlot.end(), [](int a) { return a >= 0 && a % 3 == 0; }));
    memory += saturatingMul(e.count, memoryBytes(e) + attributes * sizeof(Vec3));
    counts += (counts.empty() ? "" : ", ") + std::to_string(e.count) + " " + e.name;
  }
  requireMemory(memory, path + ": reading its elements (" + counts + ")", memoryLimit);
}

// Checks of one instance's lists that do not depend on the encoding.
class ListChecks {
 public:
  ListChecks(const Element& e, uint64_t vertices) : e_(e), vertices_(vertices) {}

  // A list's count; "" if it is acceptable, else the reason.
  std::string count(size_t p, int64_t n) {
    if (n < 0) return "list " + e_.properties[p].name + " has a negative count " + std::to_string(n);
    if (int(p) == e_.indexList) {
      if (n < 3)
        return "has " + std::to_string(n) + (n == 1 ? " vertex index" : " vertex indices") + "; a face needs at least 3";
      if (e_.trianglesOnly && n != 3)
        return "has " + std::to_string(n) + " vertex indices; a mesh with face attributes needs triangles";
      corners_ = n;
    }
    if (int(p) == e_.texcoordList) texcoords_ = n;
    return "";
  }
  // An item of list p; "" if it is acceptable.
  std::string item(size_t p, int64_t v) const {
    if (int(p) == e_.indexList && (v < 0 || uint64_t(v) >= vertices_))
      return "vertex index " + std::to_string(v) + " is not below the number of vertices, " + std::to_string(vertices_);
    return "";
  }
  // After the instance's last property.
  std::string end() const {
    if (e_.texcoordList >= 0 && texcoords_ != 2 * corners_)
      return "texcoord holds " + std::to_string(texcoords_) + " numbers for " + std::to_string(corners_) +
             " corners (two a corner)";
    return "";
  }

 private:
  const Element& e_;
  uint64_t vertices_;
  int64_t corners_ = 0, texcoords_ = 0;
};

// Binary data: walked once, without copying.
class BinaryData {
 public:
  BinaryData(std::string_view data, bool bigEndian, const std::string& path, AttributeSink& sink)
      : data_(data), bigEndian_(bigEndian), path_(path), sink_(sink) {}

  // Checks the element's instances; returns their bytes.
  std::string_view element(const Element& e, uint64_t vertices) {
    const size_t start = pos_;
    bool fixed = true;
    uint64_t size = 0;
    for (const Property& p : e.properties) fixed = fixed && !p.list, size += p.type->bytes;
    if (fixed && !e.readsAttributes()) {  // a block of equal instances
      if (saturatingMul(e.count, size) > data_.size() - pos_)
        fail(Instance{e.name, (data_.size() - pos_) / size}, "the file ends inside it (it is truncated)");
      pos_ += e.count * size;
      return data_.substr(start, pos_ - start);
    }
    for (uint64_t i = 0; i < e.count; ++i) {
      const Instance field{e.name, i};
      ListChecks lists(e, vertices);
      for (size_t p = 0; p < e.properties.size(); ++p) {
        const Property& prop = e.properties[p];
        if (!prop.list) {
          if (e.attributeSlot[p] < 0) {
            skip(prop.type->bytes, field);
          } else if (const std::string why = sink_.set(e.attributeSlot[p], i, scalar(*prop.type, field), prop); !why.empty()) {
            fail(field, why);
          }
          continue;
        }
        const int64_t n = integer(*prop.count, field);
        if (const std::string why = lists.count(p, n); !why.empty()) fail(field, why);
        if (saturatingMul(uint64_t(n), prop.type->bytes) > data_.size() - pos_)
          fail(field, "the file ends inside it (it is truncated)");
        if (int(p) != e.indexList) {
          pos_ += uint64_t(n) * prop.type->bytes;
          continue;
        }
        for (int64_t k = 0; k < n; ++k)
          if (const std::string why = lists.item(p, integer(*prop.type, field)); !why.empty()) fail(field, why);
      }
      if (const std::string why = lists.end(); !why.empty()) fail(field, why);
    }
    return data_.substr(start, pos_ - start);
  }

  void end() const {
    if (pos_ != data_.size())
      fail("data", std::to_string(data_.size() - pos_) + " bytes follow the last element the header declares");
  }

 private:
  // Which instance is read, named only in an error.
  struct Instance {
    const std::string& element;
    uint64_t index;
    operator std::string() const { return element + " " + std::to_string(index); }
  };

  [[noreturn]] void fail(const std::string& field, const std::string& reason) const {
    throw InputError(path_, field, reason);
  }

  void skip(size_t n, const Instance& field) {
    if (n > data_.size() - pos_) fail(field, "the file ends inside it (it is truncated)");
    pos_ += n;
  }

  // The bits of a value of type t in the file's byte order.
  uint64_t bits(const ScalarType& t, const Instance& field) {
    const size_t at = pos_;
    skip(t.bytes, field);
    uint64_t u = 0;
    for (size_t k = 0; k < t.bytes; ++k) {
      const unsigned char b = static_cast<unsigned char>(data_[at + (bigEndian_ ? k : t.bytes - 1 - k)]);
      u = (u << 8) | b;
    }
    return u;
  }

  // An integer of type t in the file's byte order.
  int64_t integer(const ScalarType& t, const Instance& field) {
    const uint64_t u = bits(t, field);
    const unsigned n = 8u * t.bytes;
    if (t.isSigned && (u >> (n - 1)) != 0) return int64_t(u) - (int64_t(1) << n);
    return int64_t(u);
  }

  // A number of type t (IEEE 754 floats of 4 or 8 bytes, or an integer).
  double scalar(const ScalarType& t, const Instance& field) {
    if (t.integer) return double(integer(t, field));
    const uint64_t u = bits(t, field);
    if (t.bytes == 4) {
      const uint32_t u32 = uint32_t(u);
      float f;
      std::memcpy(&f, &u32, 4);
      return f;
    }
    double d;
    std::memcpy(&d, &u, 8);
    return d;
  }

  std::string_view data_;
  bool bigEndian_;
  const std::string& path_;
  AttributeSink& sink_;
  size_t pos_ = 0;
};

// ASCII data: one line an element, rewritten as it is checked.
class AsciiData {
 public:
  AsciiData(std::string_view data, int headerLines, const std::string& path, std::string& out, AttributeSink& sink)
      : data_(data), line_(headerLines), path_(path), out_(out), sink_(sink) {}

  // Checks the element's instances, and writes them if it is passed on.
  void element(const Element& e, uint64_t vertices) {
    write_ = e.passedOn();
    for (uint64_t i = 0; i < e.count; ++i) {
      if (!nextLine())
        throw InputError(path_, "element " + e.name,
                         "the file ends after " + std::to_string(i) + " of its " + std::to_string(e.count) + " lines");
      element_ = &e.name;
      index_ = i;
      ListChecks lists(e, vertices);
      size_t t = 0;
      for (size_t p = 0; p < e.properties.size(); ++p) {
        const Property& prop = e.properties[p];
        if (!prop.list) {
          const double v = number(*prop.type, t++, e);
          if (e.attributeSlot[p] >= 0)
            if (const std::string why = sink_.set(e.attributeSlot[p], i, v, prop); !why.empty()) fail(why);
          continue;
        }
        const int64_t n = int64_t(number(*prop.count, t++, e));
        if (const std::string why = lists.count(p, n); !why.empty()) fail(why);
        for (int64_t k = 0; k < n; ++k)
          if (const std::string why = lists.item(p, int64_t(number(*prop.type, t++, e))); !why.empty()) fail(why);
      }
      if (t != tokens_.size())
        fail("has " + plural(tokens_.size(), "number") + ", more than its properties take (" + std::to_string(t) + ")");
      if (const std::string why = lists.end(); !why.empty()) fail(why);
      if (write_) out_.back() = '\n';
    }
  }

  void end() {
    if (nextLine())
      throw InputError(path_ + ":" + std::to_string(line_), "data", "a line after the last element the header declares");
  }

 private:
  [[noreturn]] void fail(const std::string& reason) const {
    throw InputError(path_ + ":" + std::to_string(line_), *element_ + " " + std::to_string(index_), reason);
  }

  // The next line that is not blank, split into tokens; false at the end of the data.
  bool nextLine() {
    while (pos_ < data_.size()) {
      const size_t end = std::min(data_.find('\n', pos_), data_.size());
      std::string_view text = data_.substr(pos_, end - pos_);
      if (!text.empty() && text.back() == '\r') text.remove_suffix(1);
      pos_ = end + 1;
      ++line_;
      tokens_ = spaceSeparatedTokens(text);
      if (!tokens_.empty()) return true;
    }
    return false;
  }

  // Token t of the line as a number of type `type` (integers exactly: they are below 2⁵³),
  // appended to the output with a space.
  double number(const ScalarType& type, size_t t, const Element& e) {
    if (t >= tokens_.size())
      fail("the line ends after " + plural(tokens_.size(), "number") + "; element " + e.name + " needs more");
    std::string_view s = tokens_[t];
    const std::string_view text = s;
    if (s.size() > 1 && s[0] == '+' && s[1] != '-') s.remove_prefix(1);
    const char* end = s.data() + s.size();
    char buf[32];
    if (type.integer) {
      int64_t v = 0;
      const auto r = std::from_chars(s.data(), end, v);
      const int64_t low = type.isSigned ? -(int64_t(1) << (8 * type.bytes - 1)) : 0;
      const int64_t high = type.isSigned ? (int64_t(1) << (8 * type.bytes - 1)) - 1 : (int64_t(1) << (8 * type.bytes)) - 1;
      if (s.empty() || r.ec != std::errc() || r.ptr != end || v < low || v > high)
        fail(shown(text) + " is not an integer from " + std::to_string(low) + " to " + std::to_string(high) + " (" +
             type.name + ")");
      if (write_) out_ += std::to_string(v) + ' ';
      return double(v);
    }
    double v = 0.0;
    const auto r = std::from_chars(s.data(), end, v);
    const bool single = type.bytes == 4;
    if (s.empty() || r.ec != std::errc() || r.ptr != end || !std::isfinite(v) || (single && !std::isfinite(float(v))))
      fail(shown(text) + " is not a finite number (" + type.name + ")");
    if (single) v = float(v);
    if (!write_) return v;
    const auto w = single ? std::to_chars(buf, buf + sizeof buf, float(v)) : std::to_chars(buf, buf + sizeof buf, v);
    out_.append(buf, w.ptr);
    out_ += ' ';
    return v;
  }

  std::string_view data_;
  int line_;
  const std::string& path_;
  std::string& out_;
  AttributeSink& sink_;
  bool write_ = false;  // whether the element being read is passed on
  const std::string* element_ = nullptr;  // the instance being read
  uint64_t index_ = 0;
  size_t pos_ = 0;
  std::vector<std::string_view> tokens_;
};

}  // namespace

std::string validatePly(const std::string& bytes, const std::string& path, uint64_t memoryLimit,
                        const std::vector<std::string>& attributes, std::vector<MeshAttribute>* read) {
  Header h = HeaderParser(bytes, path).parse();
  std::vector<MeshAttribute> found = resolveAttributes(h, attributes, path);
  const std::string_view data = std::string_view(bytes).substr(h.dataStart);
  checkCounts(h, data.size(), path, memoryLimit);
  for (MeshAttribute& a : found)  // the counts are checked against the memory limit
    for (const Element& e : h.elements)
      if (e.name == (a.perFace() ? "face" : "vertex")) a.values.assign(e.count, Vec3(0.0f));
  AttributeSink sink(found);

  std::string out = "ply\nformat ";
  out += h.format == Format::Ascii                ? "ascii"
         : h.format == Format::BinaryLittleEndian ? "binary_little_endian"
                                                  : "binary_big_endian";
  out += " 1.0\n";
  uint64_t vertices = 0;
  for (const Element& e : h.elements) {
    if (!e.passedOn()) continue;
    out += "element " + e.name + " " + std::to_string(e.count) + "\n";
    for (const Property& p : e.properties)
      out += p.list ? "property list " + std::string(p.count->name) + " " + p.type->name + " " + p.name + "\n"
                    : "property " + std::string(p.type->name) + " " + p.name + "\n";
    if (e.name == "vertex") vertices = e.count;
  }
  // assimp 5.2 takes the byte after "end_header"'s line end as the line end's second half ("\r\n")
  // and drops it if it is "\n", which the first byte of binary data can be: end with "\r\n".
  out += h.format == Format::Ascii ? "end_header\n" : "end_header\r\n";

  if (h.format == Format::Ascii) {
    out.reserve(out.size() + data.size() + data.size() / 4);
    AsciiData reader(data, h.lines, path, out, sink);
    for (const Element& e : h.elements) reader.element(e, vertices);
    reader.end();
  } else {
    BinaryData reader(data, h.format == Format::BinaryBigEndian, path, sink);
    std::vector<std::string_view> passed;
    for (const Element& e : h.elements)
      if (const std::string_view d = reader.element(e, vertices); e.passedOn()) passed.push_back(d);
    reader.end();
    for (const std::string_view d : passed) out.append(d);
  }
  if (read) *read = std::move(found);
  return out;
}

}  // namespace kasha
