#include "scene/mitsuba/xml_sensor.h"

#include <cmath>
#include <map>

#include "core/pixel_filter.h"
#include "scene/mitsuba/xml_medium.h"
#include "scene/mitsuba/xml_transform.h"

namespace kasha::mitsuba {
namespace {

using nlohmann::json;

json vec(const Vec3& v) { return {v.x, v.y, v.z}; }

// kasha's vertical field of view (degrees) of a perspective or thin-lens sensor: its `fov` along
// `fov_axis`, or (Mitsuba 3's parse_fov) a focal length "<x>mm" on a 36 × 24 mm film, 50 mm by
// default, whose angle is the diagonal's.
float fovY(XmlImport& xml, Plugin& s, int width, int height) {
  if (s.has("fov") && s.has("focal_length")) s.fail("give fov or focal_length, not both");
  float fov = 0.0f;
  std::string axis = "diagonal";
  if (s.has("fov")) {
    fov = s.number("fov");
    axis = s.string("fov_axis", "x");
  } else {
    const std::string text = s.string("focal_length", "50mm");
    const std::string mm = text.size() > 2 && text.compare(text.size() - 2, 2, "mm") == 0 ? text.substr(0, text.size() - 2) : text;
    const std::optional<std::vector<float>> f = parseNumbers(mm);
    if (!f || f->size() != 1 || !((*f)[0] > 0.0f))
      s.fail(s.property("focal_length"), "focal_length must be a positive length in mm (\"50mm\"), got '" + text + "'");
    fov = glm::degrees(2.0f * std::atan(std::sqrt(36.0f * 36.0f + 24.0f * 24.0f) / (2.0f * (*f)[0])));
    if (s.has("fov_axis")) s.note("fov_axis ignored: a focal length gives the diagonal's angle (as in Mitsuba)");
    s.string("fov_axis", "");
  }
  // tan(fov/2) below: beyond (0, 180) degrees it would wrap round to another angle.
  if (!(fov > 0.0f && fov < 180.0f)) {
    const pugi::xml_node p = s.property("fov");
    s.fail(p, "fov must be in (0, 180) degrees, got " + xml.attribute(p, "value"));
  }
  const std::optional<float> y = verticalFov(fov, axis, width, height);
  if (!y) s.fail("unknown fov_axis '" + axis + "' (x, y, diagonal, smaller, larger)");
  return *y;
}

// Mitsuba's film without an <rfilter> (Mitsuba 3 docs: hdrfilm): the Gaussian of stddev 0.5.
json defaultFilter() { return {{"type", "gaussian"}, {"stddev", 0.5f}}; }

// <rfilter> as kasha's /camera/filter (core/pixel_filter.h). Mitsuba's filters with negative lobes
// get the closest kasha has, with a note: the Gaussian of the same standard deviation where the
// kernel's second moment is positive, else the box. Mitchell–Netravali's kernel (B, C; 1/3 each
// by default) integrates to 1 and has second moment ∫x²k = (2 + 3B − 4C)/15 (its cubic pieces
// integrated), 1/9 by default; Catmull–Rom's (B = 0, C = 1/2) vanishes, and Lanczos's sinc
// interpolates too: both get the box.
json reconstructionFilter(XmlImport& xml, pugi::xml_node node) {
  Plugin f(xml, node);
  json out;
  const std::string type = f.type();
  if (type == "box") {
    out = "box";
  } else if (type == "tent") {
    out = {{"type", "tent"}, {"radius", f.number("radius", 1.0f)}};
  } else if (type == "gaussian") {
    out = defaultFilter();
    out["stddev"] = f.number("stddev", 0.5f);
  } else if (type == "mitchell" || type == "catmullrom" || type == "lanczos") {
    float variance = 0.0f;
    if (type == "mitchell") variance = (2.0f + 3.0f * f.number("B", 1.0f / 3.0f) - 4.0f * f.number("C", 1.0f / 3.0f)) / 15.0f;
    if (type == "lanczos") f.integer("lobes", 3);
    const float stddev = std::min(std::sqrt(std::max(variance, 0.0f)), PixelFilter::kMaxRadius / 4.0f);
    std::string used = "box filter";
    out = "box";
    if (stddev >= PixelFilter::kMinRadius / 4.0f) {
      out = defaultFilter();
      out["stddev"] = stddev;
      used = "gaussian filter (stddev " + std::to_string(stddev) + ")";
    }
    f.note("rendered with kasha's " + used + ", the closest it has (none with negative lobes)");
  } else {
    f.fail("unsupported rfilter plugin (box, tent, gaussian; mitchell, catmullrom, lanczos approximated)");
  }
  f.finish();
  return out;
}

}  // namespace

std::optional<float> verticalFov(float fov, const std::string& axis, int width, int height) {
  const float w = float(width), h = float(height);
  std::string a = axis;
  if (a == "smaller") a = width < height ? "x" : "y";
  if (a == "larger") a = width > height ? "x" : "y";
  const float t = std::tan(glm::radians(fov) * 0.5f);
  float ty = 0.0f;  // tan of half the vertical angle: the film's half-extents scale with its sides
  if (a == "x") ty = t * h / w;
  else if (a == "y") ty = t;
  else if (a == "diagonal") ty = t * h / std::sqrt(w * w + h * h);
  else return std::nullopt;
  return glm::degrees(2.0f * std::atan(ty));
}

void addSensor(XmlImport& xml, pugi::xml_node node, SceneJson& out) {
  Plugin s(xml, node);
  const std::string type = s.type();
  if (type != "perspective" && type != "thinlens" && type != "orthographic")
    s.fail("unsupported sensor plugin (perspective, thinlens, orthographic)");
  if (out.root.contains("camera")) s.fail("a second <sensor> (kasha renders one camera)");
  int width = 768, height = 576;
  json filter = defaultFilter();
  for (pugi::xml_node f : s.nested("film")) {
    Plugin film(xml, f);
    if (film.type() != "hdrfilm") film.fail("unsupported film plugin (hdrfilm)");
    width = film.integer("width", width);
    height = film.integer("height", height);
    for (const char* ignored : {"pixel_format", "component_format", "file_format"})
      if (film.has(ignored)) film.note(std::string("'") + ignored + "' ignored: kasha writes its own EXR and PNG");
    film.string("pixel_format", "");
    film.string("component_format", "");
    film.string("file_format", "");
    const std::vector<pugi::xml_node> rfilters = film.nested("rfilter");
    if (rfilters.size() > 1) film.fail(rfilters[1], "a second <rfilter> (a film has one reconstruction filter)");
    if (!rfilters.empty()) filter = reconstructionFilter(xml, rfilters[0]);
    film.finish();
  }
  std::vector<pugi::xml_node> samplers = s.nested("sampler"), refs;
  const std::optional<std::string> medium = endpointMedium(s, out, refs);
  for (pugi::xml_node r : refs) {
    const std::string id = xml.attribute(r, "id");
    const pugi::xml_node declared = out.declaredAs(id, "sampler");
    if (!declared) s.fail(r, "no <sampler id=\"" + id + "\"> or <medium id=\"" + id + "\"> before this reference");
    samplers.push_back(declared);
  }
  if (samplers.size() > 1) s.fail(samplers[1], "more than one sampler");
  for (pugi::xml_node smp : samplers) {
    Plugin sampler(xml, smp);
    out.root["render"]["spp"] = sampler.integer("sample_count", 4);
    sampler.note("sampler type ignored: kasha draws from its own per-sample random streams");
    sampler.integer("seed", 0);
    sampler.finish();
  }
  json camera = {{"type", type == "perspective" ? "pinhole" : type}};
  if (type != "orthographic") camera["fov"] = fovY(xml, s, width, height);
  if (s.has("near_clip") || s.has("far_clip")) s.note("near_clip and far_clip ignored (kasha does not clip)");
  s.number("near_clip", 0.0f);
  // Mitsuba's focus is at the far clip plane unless given (ProjectiveCamera); a pinhole has none,
  // and Mitsuba's perspective camera ignores it too.
  const float farClip = s.number("far_clip", 1e4f);
  const float focusDistance = s.number("focus_distance", farClip);
  if (type == "thinlens") {
    camera["aperture_radius"] = s.number("aperture_radius");
    camera["focus_distance"] = focusDistance;
  }
  const Mat4 m = toWorld(s);
  if (glm::determinant(glm::mat3(m)) < 0.0f)
    s.fail("to_world mirrors the image (a negative scale); kasha's camera cannot be mirrored");
  // Mitsuba 3's orthographic_projection: the film spans x ∈ [−1, 1], y ∈ [−1/aspect, 1/aspect] of
  // the camera's plane z = 0, which to_world scales.
  if (type == "orthographic")
    camera["extent"] = {2.0f * glm::length(transformVector(m, Vec3(1, 0, 0))),
                        2.0f * glm::length(transformVector(m, Vec3(0, 1, 0))) * float(height) / float(width)};
  const Vec3 pos = transformPoint(m, Vec3(0.0f));
  camera["position"] = vec(pos);
  camera["look_at"] = vec(pos + glm::normalize(transformVector(m, Vec3(0, 0, 1))));
  camera["up"] = vec(transformVector(m, Vec3(0, 1, 0)));
  camera["resolution"] = {width, height};
  camera["filter"] = filter;
  if (medium) camera["medium"] = *medium;
  out.root["camera"] = camera;
  out.origin("/camera", xml, node);
  s.finish();
}

void addIntegrator(XmlImport& xml, pugi::xml_node node, SceneJson& out) {
  Plugin it(xml, node);
  // Mitsuba's integrators that estimate the image kasha renders, as kasha's integrator choice
  // (render/integrator; --integrator still chooses another). Those that write something else
  // (arbitrary output variables, Stokes vectors, moments, depth) are refused.
  static const std::map<std::string, std::string> kEquivalent = {
      {"path", "pt"}, {"volpath", "pt"}, {"volpathmis", "pt"}, {"direct", "pt"}, {"ptracer", "lt"}, {"bdpt", "bdpt"}};
  const auto equivalent = kEquivalent.find(it.type());
  if (equivalent == kEquivalent.end()) {
    if (it.type() == "aov" || it.type() == "stokes" || it.type() == "moment" || it.type() == "depth")
      it.fail("integrator '" + it.type() + "' writes other quantities than radiance; kasha renders radiance only");
    it.fail("unsupported integrator plugin (path, volpath, direct, ptracer, bdpt; kasha's own with --integrator)");
  }
  out.root["render"]["integrator"] = equivalent->second;
  out.integrator = node;
  // Mitsuba counts path depth in vertices after the camera (1: emitters seen directly), kasha in
  // scattering events: one less. Mitsuba's −1 (unbounded) keeps kasha's default. `direct` is
  // emitters seen directly plus one scattering event.
  int maxDepth = -1;
  if (it.type() == "direct") {
    maxDepth = 2;
    it.note("kasha's pt with max_depth 1 (emitters seen directly and lit once); emitter_samples and bsdf_samples "
            "ignored (pt takes one light and one BSDF sample per vertex with MIS: the same image, other noise)");
    it.integer("emitter_samples", 1);
    it.integer("bsdf_samples", 1);
  } else {
    maxDepth = it.integer("max_depth", -1);
    const int rrDepth = it.integer("rr_depth", 5);
    if (rrDepth < 1) it.fail("rr_depth must be at least 1");
    out.root["render"]["rr_depth"] = rrDepth - 1;
    if (it.type() != "path")
      it.note("rendered with kasha's " + equivalent->second + " (--integrator chooses another)");
    if (it.type() == "ptracer") it.integer("samples_per_pass", 0);  // how work is split: no effect on the image
  }
  if (maxDepth == 0 || maxDepth < -1) it.fail("max_depth must be -1 or at least 1");
  if (maxDepth > 0) out.root["render"]["max_depth"] = maxDepth - 1;
  if (it.boolean("hide_emitters", false)) out.root["render"]["hide_emitters"] = true;
  out.origin("/render", xml, node);
  it.finish();
}

}  // namespace kasha::mitsuba
