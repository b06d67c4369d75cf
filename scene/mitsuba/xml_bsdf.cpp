#include "scene/mitsuba/xml_bsdf.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <vector>

#include "core/conductor_index.h"
#include "core/math.h"
#include "core/spectrum_json.h"
#include "scene/mitsuba/xml_spectrum.h"
#include "scene/mitsuba/xml_texture.h"

namespace kasha::mitsuba {
namespace {

using nlohmann::json;

// Refractive indices Mitsuba accepts by name, at the sodium D line (589 nm; CRC Handbook of
// Chemistry and Physics). Glasses with a kasha dispersion preset map to it.
json namedIor(Plugin& b, pugi::xml_node p, const std::string& name) {
  static const std::map<std::string, float> constants = {
      {"vacuum", 1.0f},       {"air", 1.000277f},          {"water", 1.3330f},        {"ethanol", 1.361f},
      {"diamond", 2.419f},    {"acrylic glass", 1.49f},    {"polypropylene", 1.49f},  {"water ice", 1.31f},
      {"pet", 1.575f},        {"sodium chloride", 1.544f}, {"glycerol", 1.4729f},     {"benzene", 1.501f}};
  if (name == "bk7") {
    b.note("int_ior 'bk7': kasha's dispersive BK7 (Sellmeier, n = 1.5168 at 587.6 nm) for Mitsuba's constant 1.5046");
    return "BK7";
  }
  if (name == "fused quartz" || name == "fused silica") return "fused_silica";
  const auto it = constants.find(name);
  if (it == constants.end()) b.fail(p, "unknown index of refraction name '" + name + "'");
  return it->second;
}

// int_ior / ext_ior: a number or a name.
json iorProperty(Plugin& b, const std::string& key, const std::string& fallback) {
  const pugi::xml_node p = b.property(key);
  if (!p) return namedIor(b, b.node(), fallback);
  if (std::string(p.name()) == "string") return namedIor(b, p, b.xml().attribute(p, "value"));
  const auto v = parseNumbers(b.xml().attribute(p, "value"));
  if (!v || v->size() != 1 || !(v->front() >= 1.0f)) b.fail(p, "expected a number >= 1 or a material name");
  return v->front();
}

// kasha takes the outside to be vacuum: a numeric int_ior becomes int/ext (the same relative
// index, hence the same directions and Fresnel terms); a dispersive preset needs ext ≈ 1.
json relativeIor(Plugin& b, const std::string& intKey, const std::string& intDefault) {
  const json in = iorProperty(b, intKey, intDefault), ext = iorProperty(b, "ext_ior", "air");
  const float e = ext.is_number() ? ext.get<float>() : 0.0f;
  if (!ext.is_number() || e > 1.001f) {
    if (!in.is_number()) b.fail("a named dispersive int_ior needs ext_ior air or vacuum (give numbers instead)");
    if (!ext.is_number()) b.fail("ext_ior must be a constant when the outside is not air");
  }
  if (in.is_number()) return in.get<float>() / e;
  return in;
}

// One roughness property: a number, or (a texture) 1 with the texture as the factor.
json roughnessValue(Plugin& b, const std::string& key, json& texture) {
  const pugi::xml_node p = b.property(key);
  if (p && isTexture(p)) {
    texture = textureField(b.xml(), p, TextureUse::Scalar);
    return 1.0;
  }
  return p ? b.number(key, 0.1f) : 0.1f;
}

// m[key] (GGX α: alpha, or alpha_u and alpha_v) and, where they are textures, m[key + "_texture"].
void roughness(Plugin& b, json& m, const std::string& key) {
  const std::string dist = b.string("distribution", "beckmann");
  if (dist != "ggx" && dist != "beckmann") b.fail("unknown microfacet distribution '" + dist + "'");
  if (dist == "beckmann") b.note("Beckmann roughness taken as GGX alpha of the same value (kasha has GGX only)");
  b.boolean("sample_visible", true);  // kasha samples visible normals always
  if (b.has("alpha_u") || b.has("alpha_v")) {
    json tu, tv;
    m[key] = json::array({roughnessValue(b, "alpha_u", tu), roughnessValue(b, "alpha_v", tv)});
    if (!tu.is_null() || !tv.is_null()) m[key + "_texture"] = json::array({tu, tv});  // null: untextured
    return;
  }
  json t;
  m[key] = roughnessValue(b, "alpha", t);
  if (!t.is_null()) m[key + "_texture"] = t;
}

// A conductor's Fresnel terms in kasha's JSON (mirror, rough_conductor): a named metal
// ("material", Mitsuba's default "none" being a perfect mirror), or η and k spectra, with
// specular_reflectance as the factor on the exact Fresnel reflectance (materials/conductor_fresnel.h).
void setConductor(Plugin& b, json& m) {
  const std::string material = b.string("material", b.has("eta") ? "" : "none");
  m["reflectance"] = spectrumProperty(b, "specular_reflectance", 1.0);
  if (material == "none") return;  // η = 0, k = 1: R = 1 at every angle, times specular_reflectance
  if (!material.empty()) {
    // Mitsuba's tables are Palik's where a name ends in _palik; kasha has one table per metal.
    std::string symbol = material;
    if (symbol.size() > 6 && symbol.ends_with("_palik")) {
      symbol.resize(symbol.size() - 6);
      b.note("'" + material + "' is kasha's measured '" + symbol + "' (scenes/spectra/conductors/" + symbol + ".csv)");
    }
    if (!namedConductor(symbol)) {
      std::string list;
      for (const std::string& n : conductorNames()) list += (list.empty() ? "" : ", ") + n;
      b.fail(b.property("material"), "no measured index for the conductor '" + material + "' in kasha (" + list +
                                         "); give <spectrum name=\"eta\"> and <spectrum name=\"k\">");
    }
    m["eta"] = symbol;
    return;
  }
  m["eta"] = spectrumProperty(b, "eta");
  m["k"] = spectrumProperty(b, "k");
}

void requireUnitSpecular(Plugin& b, const char* key) {
  const json s = spectrumProperty(b, key, 1.0);
  const auto one = [](const json& v) { return v.is_number() && v.get<float>() == 1.0f; };
  const bool rgbOne = s.is_object() && s.value("type", "") == "rgb" && s["value"].is_array() &&
                      std::all_of(s["value"].begin(), s["value"].end(), one);  // <rgb value="1"/>
  if (!one(s) && !rgbOne) b.fail(std::string("'") + key + "' other than 1 is not supported");
}

// Sets m["reflectance"] from the reflectance property `key`: a spectrum, or a texture
// (reflectance 1 times the texture's colours, xml_texture.h).
void setReflectance(Plugin& b, const std::string& key, json& m) {
  const pugi::xml_node p = b.property(key);
  if (p && isTexture(p)) {
    m["reflectance"] = 1.0;
    m["reflectance_texture"] = textureField(b.xml(), p, TextureUse::Reflectance);
  } else {
    m["reflectance"] = spectrumProperty(b, key, 0.5);
  }
}

// Sets m[key] from the scalar property `key`: a number (`fallback` if absent), or a texture
// (1 times the texture's luminance in m[key + "_texture"], xml_texture.h).
void setScalar(Plugin& b, const std::string& key, float fallback, json& m) {
  const pugi::xml_node p = b.property(key);
  if (p && isTexture(p)) {
    m[key] = 1.0;
    m[key + "_texture"] = textureField(b.xml(), p, TextureUse::Scalar);
  } else {
    m[key] = b.number(key, fallback);
  }
}

// The kasha material types a scene may use directly; each property becomes the JSON field of
// its name.
json kashaMaterial(Plugin& b) {
  json m = {{"type", b.type()}};
  for (pugi::xml_node p : b.node().children()) {
    if (p.type() != pugi::node_element) continue;
    const std::string key = b.xml().attribute(p, "name"), tag = p.name();
    b.markRead(p);
    if (tag == "boolean") {
      m[key] = b.boolean(key, false);
    } else if (tag == "string") {
      const std::string v = b.xml().attribute(p, "value");
      const bool path = key == "file" || key.ends_with("_texture");
      m[key] = path ? b.xml().resolve(p, v) : v;
    } else if (tag == "integer") {
      m[key] = b.integer(key, 0);
    } else {
      m[key] = spectrumElement(b.xml(), p);  // numbers (<float>) and spectra
    }
  }
  return m;
}

// Where a <bsdf> sits: the surface's own, inside a <twosided> (both sides), or inside another
// wrapper (a mask's, a blend's, a perturbed normal's).
enum class Placement { Surface, TwoSided, Nested };
json translate(XmlImport& xml, pugi::xml_node node, Placement placement);
Placement inside(Placement wrapper) { return wrapper == Placement::TwoSided ? Placement::TwoSided : Placement::Nested; }

// normalmap (<texture name="normalmap">, a tangent-space RGB image) and bumpmap (one <texture> of
// any name, its luminance as the height, times scale) around one nested <bsdf>: kasha's
// normal_map and bump_map (materials/normal_perturbation.h). Mitsuba flips a normal facing away
// from the incident direction (flip_invalid_normals) and dims grazing light by a shadowing
// function (use_shadowing_function); kasha uses Veach's shading-normal correction for both, noted.
json perturbedNormal(Plugin& b, Placement placement) {
  const std::vector<pugi::xml_node> inner = b.nested("bsdf");
  if (inner.size() != 1) b.fail("expected exactly one nested <bsdf>");
  json m = {{"type", b.type() == "normalmap" ? "normal_map" : "bump_map"},
            {"material", translate(b.xml(), inner.front(), inside(placement))}};
  b.boolean("flip_invalid_normals", true);
  b.boolean("use_shadowing_function", true);
  b.note("shading normals corrected as Veach 1997 does (kasha), not by Mitsuba's normal flipping and shadowing function");
  if (b.type() == "normalmap") {
    const pugi::xml_node map = b.property("normalmap");
    if (!map || !isTexture(map)) b.fail("missing <texture name=\"normalmap\">");
    m["normals"] = textureField(b.xml(), map, TextureUse::Reflectance);
    return m;
  }
  const std::vector<pugi::xml_node> height = b.nested("texture");
  if (height.size() != 1) b.fail("expected exactly one <texture> (the height)");
  m["height"] = textureField(b.xml(), height.front(), TextureUse::Scalar);
  m["scale"] = b.number("scale", 1.0f);
  return m;
}

// mask (opacity: a number, default 0.5, or a <texture> whose luminance is the opacity)
// around one nested <bsdf>: kasha's mask (materials/opacity_mask.h).
json opacityMask(Plugin& b, Placement placement) {
  const std::vector<pugi::xml_node> inner = b.nested("bsdf");
  if (inner.size() != 1) b.fail("expected exactly one nested <bsdf>");
  json m = {{"type", "mask"}, {"material", translate(b.xml(), inner.front(), inside(placement))}};
  setScalar(b, "opacity", 0.5f, m);
  return m;
}

// blendbsdf (weight: a number, default 0.5, or a <texture> whose luminance is the weight)
// of two nested <bsdf>s, in order: kasha's blend (materials/blend.h).
json blend(Plugin& b, Placement placement) {
  const std::vector<pugi::xml_node> inner = b.nested("bsdf");
  if (inner.size() != 2) b.fail("expected exactly two nested <bsdf>s, found " + std::to_string(inner.size()));
  json m = {{"type", "blend"}, {"materials", json::array()}};
  for (const pugi::xml_node component : inner) m["materials"].push_back(translate(b.xml(), component, inside(placement)));
  setScalar(b, "weight", 0.5f, m);
  return m;
}

json translate(XmlImport& xml, pugi::xml_node node, Placement placement) {
  Plugin b(xml, node);
  const std::string& t = b.type();
  json m;
  // Mitsuba's diffuse, conductors and plastics are black from behind: kasha's "one_sided", which
  // belongs to a whole surface, so a component of a mask or blend reflects on both sides.
  bool frontOnly = false;
  const auto oneSided = [&] {
    if (placement == Placement::Surface) frontOnly = true;
    if (placement == Placement::Nested)
      b.note("one-sided in Mitsuba (black from behind); kasha's component of a wrapper reflects on both sides");
  };
  if (t == "twosided") {
    const std::vector<pugi::xml_node> inner = b.nested("bsdf");
    if (inner.size() != 1) b.fail("expected exactly one nested <bsdf> (two different sides are not supported)");
    m = translate(xml, inner.front(), Placement::TwoSided);
  } else if (t == "diffuse") {
    oneSided();
    m = {{"type", "lambertian"}};
    setReflectance(b, "reflectance", m);
  } else if (t == "conductor") {
    oneSided();
    m = {{"type", "mirror"}};
    setConductor(b, m);
  } else if (t == "roughconductor") {
    oneSided();
    m = {{"type", "rough_conductor"}};
    setConductor(b, m);
    roughness(b, m, "alpha");
  } else if (t == "dielectric" || t == "roughdielectric") {
    requireUnitSpecular(b, "specular_reflectance");
    requireUnitSpecular(b, "specular_transmittance");
    m = {{"type", t == "dielectric" ? "dielectric" : "rough_dielectric"}, {"ior", relativeIor(b, "int_ior", "bk7")}};
    if (t == "roughdielectric") roughness(b, m, "alpha");
  } else if (t == "plastic" || t == "roughplastic") {
    oneSided();
    requireUnitSpecular(b, "specular_reflectance");
    // Mitsuba's nonlinear shapes the light the coat reflects back onto the base (ρ/(1 − ρ·F_dr)
    // instead of ρ/(1 − F_dr)); the approximation below leaves that light out either way.
    if (b.boolean("nonlinear", false))
      b.note("nonlinear = true acts on the light the coat reflects back onto the base, which kasha's "
             "approximation leaves out: rendered as without it");
    m = {{"type", "coated_fluorescent"}, {"absorption", 0.0}, {"emission", 1.0}, {"c", 0.0}, {"Q", 0.0},
         {"coat_ior", relativeIor(b, "int_ior", "polypropylene")}};
    setReflectance(b, "diffuse_reflectance", m);
    if (t == "roughplastic") {
      roughness(b, m, "coat_alpha");
    } else {
      m["coat_alpha"] = 0.001;
      b.note("smooth coat as GGX alpha 0.001");
    }
    b.note("plastic approximated by kasha's coated_fluorescent with c = 0: a Lambertian base under a GGX coat, "
           "without the light the coat reflects back onto the base");
  } else if (t == "jung_fluorescent" || t == "zhdanov" || t == "coated_fluorescent" || t == "measured_reradiation") {
    m = kashaMaterial(b);
  } else if (t == "mask") {
    m = opacityMask(b, placement);
  } else if (t == "blendbsdf") {
    m = blend(b, placement);
  } else if (t == "normalmap" || t == "bumpmap") {
    m = perturbedNormal(b, placement);
  } else if (t == "thindielectric") {
    requireUnitSpecular(b, "specular_reflectance");
    requireUnitSpecular(b, "specular_transmittance");
    m = {{"type", "thin_dielectric"}, {"ior", relativeIor(b, "int_ior", "bk7")}};
  } else {
    b.fail("unsupported BSDF plugin (diffuse, conductor, roughconductor, dielectric, thindielectric, roughdielectric, plastic, "
           "roughplastic, twosided, normalmap, bumpmap, mask, blendbsdf; kasha's jung_fluorescent, zhdanov, coated_fluorescent, measured_reradiation)");
  }
  if (frontOnly) m["one_sided"] = true;
  b.finish();
  return m;
}

}  // namespace

json bsdfMaterial(XmlImport& xml, pugi::xml_node bsdf) { return translate(xml, bsdf, Placement::Surface); }

bool isNullBsdf(XmlImport& xml, pugi::xml_node bsdf) {
  if (xml.optionalAttribute(bsdf, "type").value_or("") != "null") return false;
  Plugin(xml, bsdf).finish();  // claims its id; a null BSDF has no properties
  return true;
}

}  // namespace kasha::mitsuba
