#include "scene/mitsuba/xml_emitter.h"

#include <cmath>

#include "scene/mitsuba/xml_medium.h"
#include "scene/mitsuba/xml_spectrum.h"
#include "scene/mitsuba/xml_transform.h"

namespace kasha::mitsuba {
namespace {

using nlohmann::json;

json vec(const Vec3& v) { return {v.x, v.y, v.z}; }

// A bitmap <texture> that a light casts (a projector's irradiance, a spot's texture): its file as
// the light's `field`, decoded from sRGB unless `raw`.
void castBitmap(Plugin& e, pugi::xml_node texture, const std::string& field, json& light) {
  Plugin t(e.xml(), texture);
  if (t.type() != "bitmap")
    t.fail("the " + e.type() + " emitter's '" + texture.attribute("name").as_string() + "' must be a bitmap texture");
  const pugi::xml_node file = t.property("filename");
  if (!file) t.fail("missing property 'filename'");
  light[field] = e.xml().resolve(file, e.xml().attribute(file, "value"));
  light["encoding"] = t.boolean("raw", false) ? "linear" : "srgb";
  if (t.string("filter_type", "bilinear") != "nearest") t.note("kasha casts the image's texels without filtering");
  t.string("wrap_mode", "");
  t.finish();
}

// Mitsuba's spot (core/light.h): its axis from to_world; a "texture" also takes the frame's up.
json spot(Plugin& e) {
  const Mat4 m = toWorld(e);
  const float cutoff = e.number("cutoff_angle", 20.0f);
  const float beam = e.number("beam_width", cutoff * 0.75f);
  const Vec3 p = transformPoint(m, Vec3(0.0f));
  json light = {{"type", "spot"}, {"position", vec(p)}, {"look_at", vec(p + transformVector(m, Vec3(0, 0, 1)))},
                {"cone_angle", cutoff}, {"falloff_start", beam},
                {"intensity", spectrumProperty(e, "intensity", 1.0, SpectrumUse::Emission)}};
  e.note("falloff from beam_width to cutoff_angle is kasha's smooth cubic in cos θ, not Mitsuba's linear one in θ");
  if (const pugi::xml_node texture = e.property("texture")) {
    if (std::string(texture.name()) != "texture") e.fail(texture, "a spot's texture must be a bitmap <texture>");
    castBitmap(e, texture, "texture", light);
    light["up"] = vec(transformVector(m, Vec3(0, 1, 0)));
  }
  return light;
}

// Mitsuba's projector (core/projector_light.h): its frame from to_world (x left, y up, z forward),
// "fov" across the image's width (fov_axis x, Mitsuba's default), "irradiance" an <rgb> or a
// bitmap <texture>.
json projector(Plugin& e) {
  const Mat4 m = toWorld(e);
  const Vec3 p = transformPoint(m, Vec3(0.0f));
  json light = {{"type", "projector"}, {"position", vec(p)}, {"look_at", vec(p + transformVector(m, Vec3(0, 0, 1)))},
                {"up", vec(transformVector(m, Vec3(0, 1, 0)))}, {"scale", e.number("scale", 1.0f)}};
  if (e.string("fov_axis", "x") != "x") e.fail("fov_axis other than x is not supported (give the fov across the width)");
  // Without a fov, Mitsuba's 50 mm focal length on a 36 mm wide film.
  light["fov"] = e.has("fov") ? e.number("fov") : 2.0f * std::atan(18.0f / 50.0f) * 180.0f / kPi;
  const pugi::xml_node irradiance = e.property("irradiance");
  const std::string tag = irradiance ? irradiance.name() : "";
  if (!irradiance) {
    light["irradiance"] = {1.0, 1.0, 1.0};
  } else if (tag == "texture") {
    castBitmap(e, irradiance, "image", light);
  } else if (tag == "rgb" || tag == "float") {
    const std::string value = e.xml().attribute(irradiance, "value");
    const auto v = parseNumbers(value);
    if (!v || (v->size() != 1 && v->size() != 3)) e.fail(irradiance, "value '" + value + "' is not one or three numbers");
    light["irradiance"] = v->size() == 1 ? json{(*v)[0], (*v)[0], (*v)[0]} : json{(*v)[0], (*v)[1], (*v)[2]};
  } else {
    e.fail(irradiance, "a projector's irradiance must be an <rgb> or a bitmap <texture>");
  }
  return light;
}

}  // namespace

void addEmitter(XmlImport& xml, pugi::xml_node node, SceneJson& out) {
  Plugin e(xml, node);
  const std::string& t = e.type();
  json light;
  if (t == "point") {
    const pugi::xml_node pos = e.property("position");
    const Vec3 p = transformPoint(toWorld(e), pos ? parsePointProperty(xml, pos) : Vec3(0.0f));
    light = {{"type", "point"}, {"position", vec(p)}, {"intensity", spectrumProperty(e, "intensity", 1.0, SpectrumUse::Emission)}};
  } else if (t == "spot") {
    light = spot(e);
  } else if (t == "directional") {
    const pugi::xml_node d = e.property("direction");
    const Vec3 dir = d ? parsePointProperty(xml, d) : transformVector(toWorld(e), Vec3(0, 0, 1));
    light = {{"type", "distant"}, {"direction", vec(dir)}, {"irradiance", spectrumProperty(e, "irradiance", 1.0, SpectrumUse::Emission)}};
  } else if (t == "constant") {
    light = {{"type", "environment"}, {"radiance", spectrumProperty(e, "radiance", 1.0, SpectrumUse::Emission)}};
  } else if (t == "envmap") {
    if (!e.has("filename")) e.fail("missing property 'filename'");
    light = {{"type", "envmap"}, {"file", xml.resolve(node, e.string("filename", ""))},
             {"scale", e.number("scale", 1.0f)}, {"transform", matrixJson(toWorld(e))}};
  } else if (t == "projector") {
    light = projector(e);
  } else if (t == "area") {
    e.fail("an area emitter must be nested in a <shape>");
  } else {
    e.fail("unsupported emitter plugin (area, point, spot, projector, directional, constant, envmap)");
  }
  std::vector<pugi::xml_node> refs;
  if (const std::optional<std::string> medium = endpointMedium(e, out, refs)) {
    if (t != "point" && t != "spot" && t != "projector")
      e.fail("a medium around a " + t + " emitter: kasha's distant and environment light comes from outside every medium");
    light["medium"] = *medium;
  }
  if (!refs.empty()) e.fail(refs[0], "unsupported <ref> (an emitter takes a <ref> to a <medium> only)");
  e.finish();
  json& lights = out.root["lights"];
  out.origin("/lights/" + std::to_string(lights.size()), xml, node);
  lights.push_back(std::move(light));
}

}  // namespace kasha::mitsuba
