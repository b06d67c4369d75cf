#include "scene/mitsuba/xml_emitter.h"

#include "scene/mitsuba/xml_medium.h"
#include "scene/mitsuba/xml_spectrum.h"
#include "scene/mitsuba/xml_transform.h"

namespace kasha::mitsuba {
namespace {

using nlohmann::json;

json vec(const Vec3& v) { return {v.x, v.y, v.z}; }

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
    const Mat4 m = toWorld(e);
    const float cutoff = e.number("cutoff_angle", 20.0f);
    const float beam = e.number("beam_width", cutoff * 0.75f);
    const Vec3 p = transformPoint(m, Vec3(0.0f));
    light = {{"type", "spot"}, {"position", vec(p)}, {"look_at", vec(p + transformVector(m, Vec3(0, 0, 1)))},
             {"cone_angle", cutoff}, {"falloff_start", beam}, {"intensity", spectrumProperty(e, "intensity", 1.0, SpectrumUse::Emission)}};
    e.note("falloff from beam_width to cutoff_angle is kasha's smooth cubic in cos θ, not Mitsuba's linear one in θ");
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
  } else if (t == "area") {
    e.fail("an area emitter must be nested in a <shape>");
  } else {
    e.fail("unsupported emitter plugin (area, point, spot, directional, constant, envmap)");
  }
  std::vector<pugi::xml_node> refs;
  if (const std::optional<std::string> medium = endpointMedium(e, out, refs)) {
    if (t != "point" && t != "spot") e.fail("a medium around a " + t + " emitter: kasha's distant and environment light comes from outside every medium");
    light["medium"] = *medium;
  }
  if (!refs.empty()) e.fail(refs[0], "unsupported <ref> (an emitter takes a <ref> to a <medium> only)");
  e.finish();
  json& lights = out.root["lights"];
  out.origin("/lights/" + std::to_string(lights.size()), xml, node);
  lights.push_back(std::move(light));
}

}  // namespace kasha::mitsuba
