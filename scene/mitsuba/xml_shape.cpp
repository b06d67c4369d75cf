#include "scene/mitsuba/xml_shape.h"

#include <array>
#include <cmath>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "core/affine.h"
#include "scene/mitsuba/xml_bsdf.h"
#include "scene/mitsuba/xml_medium.h"
#include "scene/mitsuba/xml_spectrum.h"
#include "scene/mitsuba/xml_transform.h"

namespace kasha::mitsuba {
namespace {

using nlohmann::json;

// A planar face as kasha's rectangle: its four corners transformed, in the order that gives them
// kasha's texture coordinates (0, 0), (1, 0), (1, 1), (0, 1), and flip_normals where kasha's normal
// (p1 − p0) × (p2 − p0) would point against Mitsuba's: the local normal transformed by the inverse
// transpose (flipped by flip_normals). flipTexCoords: the corners' uv are Mitsuba's (u, v), which
// kasha, counting v from an image's bottom, reads as (u, 1 − v) (docs/mitsuba-import.md).
json face(const Mat4& m, std::array<Vec3, 4> local, Vec3 localNormal, bool flip, bool flipTexCoords) {
  std::array<Vec3, 4> w;
  for (size_t i = 0; i < 4; ++i) w[i] = transformPoint(m, local[i]);
  const Vec3 mitsubaNormal = glm::transpose(glm::inverse(glm::mat3(m))) * localNormal * (flip ? -1.0f : 1.0f);
  json c = json::array();
  for (const Vec3& p : w) c.push_back({p.x, p.y, p.z});
  return {{"type", "rectangle"},
          {"corners", c},
          {"flip_normals", glm::dot(glm::cross(w[1] - w[0], w[2] - w[0]), mitsubaNormal) < 0.0f},
          {"flip_tex_coords", flipTexCoords}};
}

// A shape's unnamed <ref>s split by what they name: a <bsdf> or a top-level area <emitter>.
struct ShapeRefs {
  std::vector<pugi::xml_node> bsdfs, emitters;  // the <ref>s, and the <emitter>s they name
};

bool namesMediumSide(pugi::xml_node n) {
  const std::string name = n.attribute("name").value();
  return name == "interior" || name == "exterior";
}

ShapeRefs shapeRefs(Plugin& s, const SceneJson& out) {
  ShapeRefs refs;
  for (pugi::xml_node r : s.nested("ref")) {
    if (namesMediumSide(r)) continue;  // shapeMedia's
    const std::string id = s.xml().attribute(r, "id");
    if (out.bsdfIds.count(id)) refs.bsdfs.push_back(r);
    else if (pugi::xml_node e = out.declaredAs(id, "emitter")) refs.emitters.push_back(e);
    else s.fail(r, "no <bsdf id=\"" + id + "\"> or area <emitter id=\"" + id + "\"> before this reference");
  }
  return refs;
}

// The shape's "interior" and "exterior" media (kasha JSON: absent is vacuum): <ref name="interior"
// id=".."/> or a nested <medium name="interior" ...>, as Mitsuba 3's shapes take them.
json shapeMedia(Plugin& s, SceneJson& out) {
  json sides = json::object();
  for (const char* side : {"interior", "exterior"}) {
    const pugi::xml_node p = s.property(side);
    if (!p) continue;
    const std::optional<std::string> medium = mediumOf(s.xml(), p, out);
    if (!medium) s.fail(p, std::string("'") + side + "' must be a <medium> or a <ref> to a <medium id> declared before");
    sides[side] = *medium;
  }
  return sides;
}

// The shape's material; "" for none (a null BSDF, or no BSDF on a shape with media): an
// index-matched medium boundary.
std::string material(Plugin& s, SceneJson& out, const ShapeRefs& refs, bool hasMedia) {
  const std::vector<pugi::xml_node> bsdfs = s.nested("bsdf");
  if (bsdfs.size() + refs.bsdfs.size() > 1) s.fail("more than one BSDF");
  if (!bsdfs.empty()) {
    if (isNullBsdf(s.xml(), bsdfs[0])) return "";
    if (const std::string* name = out.materialOf(bsdfs[0])) return *name;  // an instance's again
    return out.addMaterial(s.xml(), bsdfs[0], bsdfMaterial(s.xml(), bsdfs[0]));
  }
  if (!refs.bsdfs.empty()) return out.bsdfIds.at(s.xml().attribute(refs.bsdfs[0], "id"));
  if (hasMedia) {
    // Mitsuba 3's documentation (heterogeneous) calls this boundary index-matched; its code
    // (src/render/shape.cpp) gives every shape without a BSDF a diffuse one.
    s.note("no BSDF on a shape with media: an index-matched boundary (Mitsuba 3 renders a diffuse surface here; "
           "<bsdf type=\"null\"/> says index-matched in both)");
    return "";
  }
  // Mitsuba's default BSDF: diffuse with reflectance 0.5, one-sided.
  if (const std::string* name = out.materialOf(s.node())) return *name;
  s.note("no BSDF: Mitsuba's default, a one-sided diffuse 0.5");
  return out.addMaterial(s.xml(), s.node(), {{"type", "lambertian"}, {"reflectance", 0.5}, {"one_sided", true}});
}

json emission(Plugin& s, const ShapeRefs& refs) {
  std::vector<pugi::xml_node> emitters = s.nested("emitter");
  emitters.insert(emitters.end(), refs.emitters.begin(), refs.emitters.end());
  if (emitters.empty()) return nullptr;
  if (emitters.size() > 1) s.fail(emitters[1], "more than one emitter in a shape");
  Plugin e(s.xml(), emitters[0]);
  if (e.type() != "area") e.fail("only an 'area' emitter can be attached to a shape");
  json em = {{"radiance", spectrumProperty(e, "radiance", nullptr, SpectrumUse::Emission)}};
  e.finish();
  return em;
}

std::vector<json> geometry(Plugin& s, const Mat4& m, bool flip) {
  const std::string& t = s.type();
  if (t == "obj" || t == "ply") {
    if (!s.has("filename")) s.fail("missing property 'filename'");
    json mesh = {{"type", "mesh"}, {"file", s.xml().resolve(s.node(), s.string("filename", ""))},
                 {"transform", matrixJson(m)}, {"flip_normals", flip}};
    if (!s.boolean("face_normals", false))
      s.note("shaded with the triangles' own normals (kasha has no vertex normals): Mitsuba's face_normals = true");
    // kasha reads the file's (u, v) as they are and counts v from an image's bottom; Mitsuba
    // counts it from the top, and flips v by default for OBJ files only.
    mesh["flip_tex_coords"] = !s.boolean("flip_tex_coords", t == "obj");
    return {mesh};
  }
  if (t == "serialized") {
    if (!s.has("filename")) s.fail("missing property 'filename'");
    const int index = s.integer("shape_index", 0);
    if (index < 0) s.fail("shape_index must not be negative");
    json mesh = {{"type", "mesh"}, {"file", s.xml().resolve(s.node(), s.string("filename", ""))}, {"shape_index", index},
                 {"transform", matrixJson(m)}, {"flip_normals", flip}};
    if (s.has("face_normals")) mesh["face_normals"] = s.boolean("face_normals", false);  // else the file's flag
    return {mesh};
  }
  // Mitsuba's rectangle: uv = ((x + 1)/2, (y + 1)/2) on [−1, 1]² (src/shapes/rectangle.cpp).
  if (t == "rectangle")
    return {face(m, {Vec3(-1, -1, 0), Vec3(1, -1, 0), Vec3(1, 1, 0), Vec3(-1, 1, 0)}, Vec3(0, 0, 1), flip, true)};
  if (t == "cube") {
    // Mitsuba's cube (src/shapes/cube.cpp): per face, its normal and its four corners, whose uv
    // are (0, 1), (1, 1), (1, 0), (0, 0), so kasha's (u, 1 − v) in that order; corner c sits at
    // (±1, ±1, ±1) with bit k of c choosing the sign of axis k.
    const Vec3 normals[6] = {{0, -1, 0}, {0, 1, 0}, {1, 0, 0}, {0, 0, 1}, {-1, 0, 0}, {0, 0, -1}};
    const int corners[6][4] = {{1, 5, 4, 0}, {3, 2, 6, 7}, {1, 3, 7, 5}, {5, 7, 6, 4}, {4, 6, 2, 0}, {3, 1, 0, 2}};
    std::vector<json> faces;
    for (int side = 0; side < 6; ++side) {
      std::array<Vec3, 4> c;
      for (size_t k = 0; k < 4; ++k) {
        const int bits = corners[side][k];
        c[k] = Vec3(bits & 1 ? 1 : -1, bits & 2 ? 1 : -1, bits & 4 ? 1 : -1);
      }
      faces.push_back(face(m, c, normals[side], flip, false));
    }
    return faces;
  }
  if (t == "sphere") {
    if (flip) s.fail("flip_normals on a sphere is not supported (kasha's sphere normals point outwards)");
    // Mitsuba's sphere is its unit sphere under to_world · translate(center) · scale(radius), with
    // uv = (atan2(y, x)/2π, acos(z)/π) in its local axes (src/shapes/sphere.cpp). kasha's sphere
    // has u = 1/2 + atan2(z, x)/2π and v = acos(−y)/π in its own axes (scene-format.md), so
    // Mitsuba's local x, y, z are kasha's −x, −z, y: the same (u, 1 − v) as every imported shape.
    const pugi::xml_node c = s.property("center");
    const Vec3 center = c ? parsePointProperty(s.xml(), c) : Vec3(0.0f);
    const float radius = s.number("radius", 1.0f);
    const Mat4 local = glm::scale(glm::translate(Mat4(1.0f), center), Vec3(radius));
    const Mat4 mitsubaAxes(glm::vec4(-1, 0, 0, 0), glm::vec4(0, 0, 1, 0), glm::vec4(0, -1, 0, 0), glm::vec4(0, 0, 0, 1));
    if (!(uniformScale(glm::mat3(m * local), true) > 0.0f))
      s.fail("a sphere's to_world may only rotate, mirror, translate and scale uniformly");
    return {{{"type", "sphere"}, {"center", {0, 0, 0}}, {"radius", 1}, {"transform", matrixJson(m * local * mitsubaAxes)}}};
  }
  if (t == "cylinder") {
    // Mitsuba's defaults: p0 = (0, 0, 0), p1 = (0, 0, 1), radius 1; to_world after them.
    const pugi::xml_node p0 = s.property("p0"), p1 = s.property("p1");
    const Vec3 a = p0 ? parsePointProperty(s.xml(), p0) : Vec3(0.0f), b = p1 ? parsePointProperty(s.xml(), p1) : Vec3(0, 0, 1);
    return {{{"type", "cylinder"}, {"p0", {a.x, a.y, a.z}}, {"p1", {b.x, b.y, b.z}}, {"radius", s.number("radius", 1.0f)},
             {"transform", matrixJson(m)}, {"flip_normals", flip}}};
  }
  if (t == "disk") {
    s.note("disk tessellated into a polygon of 256 triangles (area 0.01% below the disk's)");
    // Mitsuba's disk normal is the transformed local +z, which a mirroring to_world does not turn
    // as it turns kasha's winding; its uv = (r, φ/2π) is kasha's disk's with v counted from the top.
    const bool mirrors = glm::determinant(glm::mat3(m)) < 0.0f;
    return {{{"type", "disk"}, {"transform", matrixJson(m)}, {"flip_normals", flip != mirrors}, {"flip_tex_coords", true}}};
  }
  s.fail("unsupported shape plugin (obj, ply, serialized, rectangle, cube, sphere, disk, cylinder, shapegroup, instance)");
}

// One shape (not a group), placed by `outer` after its own to_world and named `prefix` + its id or
// label: the shapes a <shape> element gives, appended to `out`.
void addPlacedShape(XmlImport& xml, pugi::xml_node node, SceneJson& out, const Mat4& outer, const std::string& prefix) {
  Plugin s(xml, node);
  const Mat4 m = outer * toWorld(s);
  const bool flip = s.boolean("flip_normals", false);
  std::vector<json> parts = geometry(s, m, flip);
  const ShapeRefs refs = shapeRefs(s, out);
  const json media = shapeMedia(s, out);
  const std::string mat = material(s, out, refs, !media.empty());
  if (mat.empty() && media.empty()) s.fail("a null BSDF on a shape without media (an invisible shape; kasha has none)");
  if (s.type() == "cube" && media.value("interior", "") != media.value("exterior", ""))
    s.fail("a cube with different media inside and outside: kasha's cube is six rectangles, not a closed surface "
           "(use an obj or ply box)");
  const json em = emission(s, refs);
  const std::string base = prefix + (node.attribute("id") ? xml.attribute(node, "id") : xml.label(node));
  json& shapes = out.root["shapes"];
  for (size_t i = 0; i < parts.size(); ++i) {
    json& p = parts[i];
    p["name"] = parts.size() == 1 ? base : base + "/" + std::to_string(i);
    if (!mat.empty()) p["material"] = mat;
    p.update(media);
    if (!em.is_null()) p["emission"] = em;
    out.origin("/shapes/" + std::to_string(shapes.size()), xml, node);
    shapes.push_back(std::move(p));
  }
  s.finish();
}

// Mitsuba's shapegroup (Mitsuba 3 docs: shapegroup): shapes that appear only through instances.
// Checked where it is declared, with Mitsuba's rules (src/render/shapegroup.cpp): no groups or
// instances inside, no emitters.
void declareShapeGroup(Plugin& g, const SceneJson& out) {
  if (!g.node().attribute("id")) g.fail("a shapegroup needs an id for its instances to refer to");
  const std::vector<pugi::xml_node> members = g.nested("shape");
  if (members.empty()) g.fail("a shapegroup without shapes");
  for (pugi::xml_node n : members) {
    Plugin s(g.xml(), n);  // refuses a plugin outside kasha's scope at its own line
    if (s.type() == "shapegroup" || s.type() == "instance") s.fail("a " + s.type() + " inside a shapegroup (Mitsuba permits no nesting)");
    if (!s.nested("emitter").empty()) s.fail("an emitter in a shapegroup (Mitsuba does not instance emitters)");
    for (pugi::xml_node r : s.nested("ref"))
      if (!namesMediumSide(r) && out.declaredAs(s.xml().attribute(r, "id"), "emitter"))
        s.fail(r, "an emitter in a shapegroup (Mitsuba does not instance emitters)");
  }
  g.finish();
}

// Mitsuba's instance: its shapegroup's shapes, each placed by the instance's to_world after its
// own. kasha copies them into the scene (no shared acceleration structure: memory grows with the
// number of instances, checked against the memory limit as any geometry).
void addInstance(Plugin& inst, SceneJson& out) {
  XmlImport& xml = inst.xml();
  const std::vector<pugi::xml_node> refs = inst.nested("ref");
  if (refs.size() != 1) inst.fail("an instance takes exactly one <ref id=\"..\"/> to a shapegroup");
  const std::string id = xml.attribute(refs[0], "id");
  const pugi::xml_node group = xml.declared("shape", id);
  if (!group || std::string(group.attribute("type").value()) != "shapegroup")
    inst.fail(refs[0], "no <shape type=\"shapegroup\" id=\"" + id + "\"> before this reference");
  const Mat4 m = toWorld(inst);
  const std::string prefix = (inst.node().attribute("id") ? xml.attribute(inst.node(), "id") : xml.label(inst.node())) + "/";
  for (pugi::xml_node n : group.children("shape")) addPlacedShape(xml, n, out, m, prefix);
  inst.finish();
}

}  // namespace

void addShape(XmlImport& xml, pugi::xml_node node, SceneJson& out) {
  const std::string type = node.attribute("type") ? xml.attribute(node, "type") : "";
  if (type != "shapegroup" && type != "instance") return addPlacedShape(xml, node, out, Mat4(1.0f), "");
  Plugin p(xml, node);
  if (type == "shapegroup") declareShapeGroup(p, out);
  else addInstance(p, out);
}

}  // namespace kasha::mitsuba
