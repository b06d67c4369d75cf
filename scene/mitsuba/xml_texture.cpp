#include "scene/mitsuba/xml_texture.h"

#include "scene/mitsuba/xml_transform.h"

namespace kasha::mitsuba {
namespace {

using nlohmann::json;

json bitmap(Plugin& t, TextureUse use) {
  const pugi::xml_node file = t.property("filename");
  if (!file) t.fail("missing property 'filename'");
  const std::string name = t.xml().attribute(file, "value");
  // A scalar reads the luminance of R, G, B, as Mitsuba's eval_1 does (src/textures/bitmap.cpp).
  json out = {{"file", t.xml().resolve(file, name)}, {"channel", use == TextureUse::Scalar ? "luminance" : "rgb"}};
  const std::string filter = t.string("filter_type", "bilinear");
  if (filter != "bilinear" && filter != "nearest") t.fail("filter_type '" + filter + "' is not bilinear or nearest");
  out["filter"] = filter;
  const std::string wrap = t.string("wrap_mode", "repeat");
  if (wrap != "repeat" && wrap != "mirror" && wrap != "clamp")
    t.fail("wrap_mode '" + wrap + "' is not repeat, mirror or clamp");
  out["wrap"] = wrap;
  out["encoding"] = t.boolean("raw", false) ? "linear" : "srgb";
  return out;
}

// A checkerboard colour: a number, or [r, g, b] (a reflectance's; a scalar reads the mean of a
// colour, as Mitsuba's eval_1 of an sRGB spectrum takes its mean).
json checkerColour(Plugin& t, const std::string& key, float fallback, TextureUse use) {
  const pugi::xml_node p = t.property(key);
  if (!p) return fallback;
  const std::string tag = p.name();
  if (tag != "float" && tag != "rgb" && !(tag == "spectrum" && !p.attribute("type") && !p.attribute("filename")))
    t.fail(p, "a checkerboard colour must be a <float>, an <rgb> or a constant <spectrum>, not <" + tag + ">");
  const std::string value = t.xml().attribute(p, "value");
  const auto v = parseNumbers(value);
  if (!v || (v->size() != 1 && !(tag == "rgb" && v->size() == 3)))
    t.fail(p, "value '" + value + "' is not " + (tag == "rgb" ? "one or three numbers" : "a number"));
  if (v->size() == 1) return v->front();
  if (use == TextureUse::Scalar) return ((*v)[0] + (*v)[1] + (*v)[2]) / 3.0f;
  return *v;
}

json checkerboard(Plugin& t, TextureUse use) {
  // Mitsuba 3 (src/textures/checkerboard.cpp) reads color0 where the fractional parts of u and v
  // are on the same side of ½ in eval(), the spectrum, but where they are on different sides in
  // eval_1(), the scalar a roughness reads: the colours swap places for scalar uses.
  const bool swap = use == TextureUse::Scalar;
  json out = {{"type", "checkerboard"},
              {"color0", checkerColour(t, swap ? "color1" : "color0", swap ? 0.2f : 0.4f, use)},
              {"color1", checkerColour(t, swap ? "color0" : "color1", swap ? 0.4f : 0.2f, use)}};
  // Mitsuba's 4×4 to_uv → 2×3: the upper-left 2×2 and the translation column's first two rows.
  Mat4 m(1.0f);
  if (const pugi::xml_node uv = t.property("to_uv")) {
    if (std::string(uv.name()) != "transform") t.fail(uv, "to_uv must be a <transform>");
    m = parseTransform(t.xml(), uv);
  }
  // The imported shapes give kasha (u, 1 − v) where Mitsuba has (u, v) (docs/mitsuba-import.md),
  // so kasha's to_uv is Mitsuba's after v ← 1 − v: (a, b, c) · (u, 1 − v, 1) = (a, −b, b + c) · (u, v, 1).
  out["to_uv"] = {{m[0][0], -m[1][0], m[1][0] + m[3][0]}, {m[0][1], -m[1][1], m[1][1] + m[3][1]}};
  return out;
}

json meshAttribute(Plugin& t) {
  const std::string name = t.string("name", "");
  if (!name.starts_with("vertex_") && !name.starts_with("face_"))
    t.fail("name '" + name + "' is not a mesh attribute's (vertex_... or face_...)");
  if (t.number("scale", 1.0f) != 1.0f) t.fail("a scale other than 1 is not supported");
  return {{"type", "mesh_attribute"}, {"name", name}};
}

}  // namespace

bool isTexture(pugi::xml_node p) {
  const std::string tag = p.name();
  return tag == "texture" || tag == "ref";
}

json textureField(XmlImport& xml, pugi::xml_node p, TextureUse use) {
  pugi::xml_node node = p;
  if (std::string(p.name()) == "ref") {
    const std::string id = xml.attribute(p, "id");
    node = xml.declared("texture", id);
    if (!node) xml.fail(p, "no <texture id=\"" + id + "\"> before this reference");
  }
  Plugin t(xml, node);
  json out;
  if (t.type() == "bitmap") out = bitmap(t, use);
  else if (t.type() == "checkerboard") out = checkerboard(t, use);
  else if (t.type() == "mesh_attribute") out = meshAttribute(t);
  else t.fail("unsupported texture plugin (bitmap, checkerboard, mesh_attribute)");
  t.finish();
  return out;
}

}  // namespace kasha::mitsuba
