#include "scene/scene_loader.h"

#include <tiny_obj_loader.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <vector>

#include "core/affine.h"
#include "core/envmap_light.h"
#include "core/input_file.h"
#include "core/json_fields.h"
#include "core/json_parse.h"
#include "core/mesh_builders.h"
#include "core/memory_budget.h"
#include "core/obj_validation.h"
#include "core/serialized_mesh.h"
#include "core/spectrum_json.h"
#include "core/spectrum_presets.h"
#include "core/texture.h"
#include "materials/material_json.h"
#include "core/projector_light.h"
#include "materials/medium_json.h"
#include "scene/medium_consistency.h"
#include "scene/mitsuba/mitsuba_scene.h"

namespace kasha {
namespace {

using nlohmann::json;

// Reading an OBJ file takes about this many times its size in memory (tinyobjloader's arrays,
// kasha's positions, indices and normals, Embree's BVH): measured on meshes of 10⁴–10⁶ triangles;
// one more for the file's text, read whole before parsing. A PLY file is held to it too, and its
// declared elements are checked against the limit on their own (core/ply_validation.h).
constexpr uint64_t kMeshBytesPerFileByte = 7;
// Named spectra may refer to each other; no sensible chain of names is longer than this, and a
// limit keeps the recursion through the references bounded.
constexpr size_t kMaxSpectrumReferenceDepth = 64;
// Triangles of a "disk" shape: its area is 1 − 1.0·10⁻⁴ of the disk's.
constexpr int kDiskSegments = 256;

struct Loader {
  std::string file;
  SpectrumContext ctx;
  std::map<std::string, Spectrum> named;
  std::map<std::string, uint32_t> materialIndex;
  std::map<std::string, int> mediumIndex;
  std::string cameraMedium;  // /camera/medium, resolved once /media is read
  Scene& scene;
  SceneLoadOptions options;
  const json* spectraJson = nullptr;
  std::vector<std::string> resolving;  // named spectra being parsed, to detect cycles
  TextureLoader textures;

  Loader(std::string f, Scene& s, SceneLoadOptions o)
      : file(std::move(f)), scene(s), options(o), textures(o.memoryLimit) {
    ctx.file = file;
    ctx.baseDir = std::filesystem::path(file).parent_path().string();
    if (ctx.baseDir.empty()) ctx.baseDir = ".";
    ctx.named = &named;
    ctx.range = &scene.range;
    ctx.textures = &textures;
    ctx.memoryLimit = options.memoryLimit;
    ctx.resolveName = [this](const std::string& name, const std::string& ptr) { return namedSpectrum(name, ptr); };
  }

  // The entry `name` of /spectra, parsed on first use, so entries may refer to each other in any
  // order; a cycle of references is an error. nullptr if there is no such entry.
  const Spectrum* namedSpectrum(const std::string& name, const std::string& ptr) {
    if (auto it = named.find(name); it != named.end()) return &it->second;
    if (!spectraJson || !spectraJson->contains(name)) return nullptr;
    const auto loop = std::find(resolving.begin(), resolving.end(), name);
    if (loop != resolving.end()) {
      std::string chain;
      for (auto it = loop; it != resolving.end(); ++it) chain += *it + " -> ";
      std::string hint;
      if (presetSpectrum(name)) hint = " (for the preset write {\"type\": \"preset\", \"name\": \"" + name + "\"})";
      throw InputError(file, ptr, "named spectra refer to each other in a cycle: " + chain + name + hint);
    }
    if (resolving.size() >= kMaxSpectrumReferenceDepth)
      throw InputError(file, ptr, "named spectra refer to each other more than " +
                                      std::to_string(kMaxSpectrumReferenceDepth) + " deep (from '" + resolving.front() +
                                      "' to '" + name + "')");
    resolving.push_back(name);
    Spectrum s = parseSpectrum(spectraJson->at(name), ctx, "/spectra/" + name);
    resolving.pop_back();
    return &(named[name] = std::move(s));
  }

  std::string resolve(const std::string& rel) const { return ctx.resolve(rel); }

  // A light's spectrum must put some energy into the scene's range.
  Spectrum emitterSpectrum(JsonFields& f, const std::string& key) {
    Spectrum s = parseSpectrum(f.get(key), ctx, f.path(key));
    if (!std::isfinite(s.integral(scene.range)))
      f.fail(key, "emission over the wavelength range overflows a 32-bit float");
    if (!(s.integral(scene.range) > 0.0f))
      f.fail(key, "emission integrates to zero over the wavelength range [" + std::to_string(int(scene.range.min)) +
                      ", " + std::to_string(int(scene.range.max)) + "] nm");
    return s;
  }

  // The "scale" of an emitter whose spectrum is `spectrum`: positive, and not so large that the
  // emitted power overflows.
  float scaleField(JsonFields& f, const Spectrum& spectrum) {
    const float s = f.number("scale", 1.0f);
    if (!(s > 0.0f)) f.fail("scale", "must be positive");
    if (!std::isfinite(s * spectrum.integral(scene.range)))
      f.fail("scale", "the scaled emission overflows a 32-bit float over the wavelength range");
    return s;
  }

  void range(JsonFields& root) {
    if (!root.has("wavelength_range")) return;
    const json& r = root.get("wavelength_range");
    if (!r.is_array() || r.size() != 2 || !r[0].is_number() || !r[1].is_number())
      root.fail("wavelength_range", "expected [min, max] in nm");
    scene.range = {r[0].get<float>(), r[1].get<float>()};
    if (!(scene.range.min >= 200.0f && scene.range.max <= 2500.0f && scene.range.min < scene.range.max))
      root.fail("wavelength_range", "expected 200 <= min < max <= 2500 nm");
    if (scene.range.max <= 360.0f || scene.range.min >= 830.0f)
      root.fail("wavelength_range", "does not overlap the visible range 360-830 nm");
  }

  void render(JsonFields& root) {
    if (!root.has("render")) return;
    JsonFields f(root.get("render"), file, "/render");
    RenderSettings& r = scene.render;
    r.integrator = f.string("integrator", r.integrator);
    r.spp = f.integer("spp", r.spp);
    if (r.spp < 1) f.fail("spp", "must be at least 1");
    r.timeBudgetSeconds = f.number("time", 0.0f);
    if (r.timeBudgetSeconds < 0.0) f.fail("time", "must not be negative");
    r.maxDepth = f.integer("max_depth", r.maxDepth);
    if (r.maxDepth < 0) f.fail("max_depth", "must not be negative");
    r.rrDepth = f.integer("rr_depth", r.rrDepth);
    r.hideEmitters = f.boolean("hide_emitters", r.hideEmitters);
    if (r.rrDepth < 0) f.fail("rr_depth", "must not be negative");
    const int seed = f.integer("seed", int(r.seed));
    if (seed < 0) f.fail("seed", "must not be negative");
    r.seed = uint64_t(seed);
    const std::string sampler = f.string("sampler", toString(r.sampler));
    if (const auto kind = parseSamplerKind(sampler)) r.sampler = *kind;
    else f.fail("sampler", "'" + sampler + "' is not a sampler (sobol, independent)");
    wavelengthSpec(f, "sensor_sampling", r.wavelengths.sensor);
    wavelengthSpec(f, "fluorescence_sampling", r.wavelengths.fluorescence);
    wavelengthSpec(f, "light_sampling", r.wavelengths.light);
    wavelengthSpec(f, "nee_sampling", r.wavelengths.nee);
    r.heroWavelengths = f.integer("hero_wavelengths", r.heroWavelengths);
    if (r.heroWavelengths < 0 || r.heroWavelengths > 16)
      f.fail("hero_wavelengths", "must be in [1, 16], or 0 for the integrator's default");
    const std::string lanes = f.string("fluorescent_lanes", toString(r.fluorescentLanes));
    if (const auto at = parseFluorescentLanes(lanes)) r.fluorescentLanes = *at;
    else f.fail("fluorescent_lanes", "'" + lanes + "' is not what lanes do at fluorescent events (through, end)");
    // The integrators' own settings, each in its object (before session 20's consolidation they
    // were spread over the render object; say where they went).
    for (const auto& [old, now] : {std::pair{"bdpt_families", "render/bdpt/families"}, std::pair{"vcm_paths", "render/vcm/paths"},
                                   std::pair{"mollify", "render/bdpt/mollify, mollify_bandwidth and mollify_alpha"}})
      if (f.has(old)) f.fail(old, std::string("is now ") + now + " (docs/scene-format.md)");
    bdpt(f);
    vcm(f);
    photonMapping(f);
    f.finish();
  }

  // A wavelength strategy's text (core/wavelength_spec.h); whether it applies is checked when the
  // integrator is built.
  static void wavelengthSpec(JsonFields& f, const char* key, WavelengthSpec& out) {
    const std::string text = f.string(key, out.text);
    try {
      out = parseWavelengthSpec(text);
    } catch (const std::exception& e) {
      f.fail(key, e.what());
    }
  }

  // The light-vertex pass and the radii of /render/ppm and /render/vcm.
  static void progressive(JsonFields& f, ProgressiveSettings& p) {
    p.photonsPerPass = f.integer("photons_per_pass", p.photonsPerPass);
    p.radius = f.number("radius", p.radius);
    p.alpha = f.number("alpha", p.alpha);
    p.bandwidth = f.number("bandwidth", p.bandwidth);
    p.volumeRadius = f.number("volume_radius", p.volumeRadius);
    checkProgressiveSettings(p, [&](const char* key, const std::string& why) { f.fail(key, why); });
  }

  // /render/ppm (docs/photon-mapping.md).
  void photonMapping(JsonFields& render) {
    if (!render.has("ppm")) return;
    JsonFields f(render.get("ppm"), file, render.path("ppm"));
    PhotonMappingSettings& p = scene.render.ppm;
    progressive(f, p);
    p.alwaysKernel = f.boolean("always_wavelength_kernel", p.alwaysKernel);
    const std::string direct = f.string("direct", "nee-elastic");
    if (direct == "nee-elastic") p.direct = PpmDirectLight::NeeElastic;
    else if (direct == "nee") p.direct = PpmDirectLight::Nee;
    else if (direct == "photons") p.direct = PpmDirectLight::Photons;
    else f.fail("direct", "expected \"nee-elastic\", \"nee\" or \"photons\"");
    p.neeWavelengths = f.string("nee_wavelengths", p.neeWavelengths);
    if (const std::string why = ppmNeeWavelengthsError(p.neeWavelengths); !why.empty()) f.fail("nee_wavelengths", why);
    f.finish();
  }

  // /render/vcm (docs/bdpt-mis.md §12, §14).
  void vcm(JsonFields& render) {
    if (!render.has("vcm")) return;
    JsonFields f(render.get("vcm"), file, render.path("vcm"));
    VcmSettings& v = scene.render.vcm;
    progressive(f, v);
    const std::string paths = f.string("paths", toString(v.paths));
    if (const auto choice = parseVcmPaths(paths)) v.paths = *choice;
    else f.fail("paths", "'" + paths + "' is not a choice of vcm's subpaths (auto, bidirectional, gather, connections, camera)");
    v.beams = f.boolean("beams", v.beams);
    v.photonBeams = f.boolean("photon_beams", v.photonBeams);
    f.finish();
  }

  // /render/bdpt (docs/bdpt-mis.md §6, §13).
  void bdpt(JsonFields& render) {
    if (!render.has("bdpt")) return;
    JsonFields f(render.get("bdpt"), file, render.path("bdpt"));
    BdptSettings& b = scene.render.bdpt;
    const std::string families = f.string("families", toString(b.families));
    if (const auto choice = parseBdptFamilies(families)) b.families = *choice;
    else f.fail("families", "'" + families + "' is not a choice of bdpt's light subpaths (auto, both, shared, own)");
    b.mollify = f.boolean("mollify", b.mollify);
    b.mollifyBandwidth = f.number("mollify_bandwidth", b.mollifyBandwidth);
    b.mollifyAlpha = f.number("mollify_alpha", b.mollifyAlpha);
    checkBdptSettings(b, [&](const char* key, const std::string& why) { f.fail(key, why); });
    f.finish();
  }

  void camera(JsonFields& root) {
    JsonFields f(root.get("camera"), file, "/camera");
    const Vec3 pos = f.vec3("position"), at = f.vec3("look_at"), up = f.vec3("up", Vec3(0, 1, 0));
    const std::string type = f.string("type", "pinhole");
    cameraMedium = f.string("medium", "");
    if (type != "pinhole" && type != "thinlens" && type != "orthographic")
      f.fail("type", "'" + type + "' is not a camera (pinhole, thinlens, orthographic)");
    float fov = 0.0f;
    Vec2 extent(0.0f);
    if (type == "orthographic") {
      const json& e = f.get("extent");
      if (!e.is_array() || e.size() != 2 || !e[0].is_number() || !e[1].is_number())
        f.fail("extent", "expected [width, height] of the film in scene units");
      extent = Vec2(e[0].get<float>(), e[1].get<float>());
      if (!(extent.x > 0.0f && extent.y > 0.0f && std::isfinite(extent.x) && std::isfinite(extent.y)))
        f.fail("extent", "the film's width and height must be positive and finite");
    } else {
      fov = f.number("fov");
      if (!(fov > 0.0f && fov < 180.0f)) f.fail("fov", "vertical field of view must be in (0, 180) degrees");
    }
    float aperture = 0.0f, focus = 1.0f;
    if (type == "thinlens") {
      aperture = f.number("aperture_radius");
      if (!(aperture >= 0.0f && std::isfinite(aperture))) f.fail("aperture_radius", "must be finite and at least 0");
      focus = f.number("focus_distance");
      if (!(focus > 0.0f && std::isfinite(focus))) f.fail("focus_distance", "must be positive and finite");
    }
    const json& res = f.get("resolution");
    if (!res.is_array() || res.size() != 2 || !res[0].is_number_integer() || !res[1].is_number_integer())
      f.fail("resolution", "expected [width, height] in pixels");
    const int64_t w = res[0].get<int64_t>(), h = res[1].get<int64_t>();  // int64: 2^32 + 8 must not wrap to 8
    if (w < 1 || h < 1 || w > 16384 || h > 16384) f.fail("resolution", "width and height must be in 1..16384");
    const Vec3 fwd = at - pos;
    if (!(glm::length(fwd) > 0.0f)) f.fail("look_at", "equals /camera/position");
    // The lengths first: a product of finite but huge lengths overflows and would blame "up".
    if (!std::isfinite(glm::length(fwd)))
      f.fail("look_at", "is too far from /camera/position (their distance overflows a 32-bit float)");
    if (!(glm::length(up) > 0.0f)) f.fail("up", "must not be zero");
    if (!std::isfinite(glm::length(up))) f.fail("up", "is too long (its length overflows a 32-bit float)");
    if (!(glm::length(glm::cross(fwd / glm::length(fwd), up / glm::length(up))) > 1e-6f))
      f.fail("up", "is parallel to the viewing direction");
    if (f.has("filter")) scene.pixelFilter = pixelFilter(f);
    f.finish();
    if (type == "pinhole") scene.camera = Camera(pos, at, up, fov, int(w), int(h));
    else if (type == "thinlens") scene.camera = Camera::thinLens(pos, at, up, fov, int(w), int(h), aperture, focus);
    else scene.camera = Camera::orthographic(pos, at, up, extent, int(w), int(h));
  }

  // /camera/filter: "box", "tent", "gaussian" or {"type": …, "radius" (tent) / "stddev" (gaussian)}.
  PixelFilter pixelFilter(JsonFields& cam) {
    const json& v = cam.get("filter");
    if (!v.is_string()) return pixelFilter(v, cam.path("filter"));
    const std::string type = v.get<std::string>();
    if (type != "box" && type != "tent" && type != "gaussian")
      cam.fail("filter", "unknown reconstruction filter '" + type + "' (box, tent, gaussian)");
    return pixelFilter(json{{"type", type}}, cam.path("filter"));
  }
  PixelFilter pixelFilter(const json& v, const std::string& pointer) {
    JsonFields f(v, file, pointer);
    const std::string type = f.string("type");
    // The supports PixelFilter accepts, kMinRadius = 1/64 to kMaxRadius = 16 pixels.
    const float lo = PixelFilter::kMinRadius, hi = PixelFilter::kMaxRadius;
    PixelFilter filter;
    if (type == "tent") {
      const float radius = f.number("radius", 1.0f);
      if (!(radius >= lo && radius <= hi)) f.fail("radius", "must be in [1/64, 16] pixels");
      filter = PixelFilter::tent(radius);
    } else if (type == "gaussian") {
      const float stddev = f.number("stddev", 0.5f);
      if (!(stddev >= lo / 4.0f && stddev <= hi / 4.0f))
        f.fail("stddev", "must be in [1/256, 4] pixels (the support reaches 4 standard deviations)");
      filter = PixelFilter::gaussian(stddev);
    } else if (type != "box") {
      f.fail("type", "unknown reconstruction filter '" + type + "' (box, tent, gaussian)");
    }
    f.finish();
    return filter;
  }

  void spectra(JsonFields& root) {
    if (!root.has("spectra")) return;
    const json& s = root.get("spectra");
    if (!s.is_object()) root.fail("spectra", "expected an object of named spectra");
    spectraJson = &s;
    for (auto it = s.begin(); it != s.end(); ++it) namedSpectrum(it.key(), "/spectra/" + it.key());
  }

  void materials(JsonFields& root) {
    const json& m = root.get("materials");
    if (!m.is_object() || m.empty()) root.fail("materials", "expected an object of named materials");
    for (auto it = m.begin(); it != m.end(); ++it) {
      materialIndex[it.key()] = uint32_t(scene.materials.size());
      scene.materialNames.push_back(it.key());
      scene.materials.push_back(parseMaterial(it.value(), ctx, "/materials/" + it.key(), scene.range));
    }
  }

  // /media: named participating media (materials/medium_json.h); then the camera's medium.
  void media(JsonFields& root) {
    if (root.has("media")) {
      const json& m = root.get("media");
      if (!m.is_object()) root.fail("media", "expected an object of named media");
      for (auto it = m.begin(); it != m.end(); ++it) {
        mediumIndex[it.key()] = int(scene.media.size());
        scene.media.push_back(parseMedium(it.key(), it.value(), ctx, "/media/" + it.key(), scene.range));
        scene.mediumScattering.push_back(std::make_unique<VolumeScattering>(*scene.media.back()));
      }
    }
    if (!cameraMedium.empty()) scene.cameraMedium = mediumNamed(cameraMedium, file, "/camera/medium");
  }

  // The index of the medium `name` in /media; an InputError at `field` if there is none.
  int mediumNamed(const std::string& name, const std::string& where, const std::string& field) const {
    const auto it = mediumIndex.find(name);
    if (it == mediumIndex.end()) throw InputError(where, field, "no medium named '" + name + "' in /media");
    return it->second;
  }

  // A shape's media: "interior" and "exterior" (either may be absent: vacuum), or "medium" for the
  // same medium on both sides (a shape immersed in it, such as an emitter).
  std::optional<MediumInterface> mediumInterface(JsonFields& f) const {
    const bool sides = f.has("interior") || f.has("exterior");
    if (f.has("medium") && sides) f.fail("medium", "give either medium or interior/exterior");
    if (f.has("medium")) {
      const int m = mediumNamed(f.string("medium"), file, f.path("medium"));
      return MediumInterface{m, m};
    }
    if (!sides) return std::nullopt;
    MediumInterface mi;
    if (f.has("interior")) mi.interior = mediumNamed(f.string("interior"), file, f.path("interior"));
    if (f.has("exterior")) mi.exterior = mediumNamed(f.string("exterior"), file, f.path("exterior"));
    return mi;
  }

  void loadObj(JsonFields& f, Shape& s) {
    const std::string path = resolve(f.string("file"));
    tinyobj::ObjReaderConfig cfg;
    cfg.triangulate = true;
    cfg.vertex_color = false;
    tinyobj::ObjReader reader;
    std::string text = readMeshFile(f, path);
    try {
      text = validateObjText(text, path);
    } catch (const InputError& e) {
      f.fail("file", e.what());
    }
    if (!reader.ParseFromString(text, "", cfg)) f.fail("file", "'" + path + "': " + reader.Error());
    const auto& v = reader.GetAttrib().vertices;
    for (size_t i = 0; i + 2 < v.size(); i += 3) {
      const Vec3 p(v[i], v[i + 1], v[i + 2]);
      if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
        f.fail("file", "'" + path + "': vertex " + std::to_string(i / 3 + 1) + " is not finite");
      s.positions.push_back(p);
    }
    for (const auto& shape : reader.GetShapes())
      for (const auto& idx : shape.mesh.indices) {
        if (s.indices.size() >= size_t(UINT32_MAX)) f.fail("file", "'" + path + "': more than 2^32 vertex indices");
        if (idx.vertex_index < 0 || size_t(idx.vertex_index) >= s.positions.size())
          f.fail("file", "'" + path + "': face refers to a missing vertex");
        s.indices.push_back(uint32_t(idx.vertex_index));
        if (idx.texcoord_index >= 0 && 2 * size_t(idx.texcoord_index) + 1 < reader.GetAttrib().texcoords.size()) {
          const float* t = &reader.GetAttrib().texcoords[2 * size_t(idx.texcoord_index)];
          s.cornerUvs.emplace_back(t[0], t[1]);
        }
        if (idx.normal_index >= 0 && 3 * size_t(idx.normal_index) + 2 < reader.GetAttrib().normals.size()) {
          const float* n = &reader.GetAttrib().normals[3 * size_t(idx.normal_index)];
          s.cornerNormals.emplace_back(n[0], n[1], n[2]);
        }
      }
    if (!s.cornerUvs.empty() && s.cornerUvs.size() != s.indices.size())
      f.fail("file", "'" + path + "': some faces have texture coordinates (vt) and some do not");
    if (!s.cornerNormals.empty() && s.cornerNormals.size() != s.indices.size())
      f.fail("file", "'" + path + "': some faces have vertex normals (vn) and some do not");
    scaleAndTranslate(f, s);
  }

  // The bytes of a mesh file (OBJ or PLY), opened as every input is (core/input_file.h) and read
  // only if reading it fits the memory limit.
  std::string readMeshFile(JsonFields& f, const std::string& path) {
    try {
      InputFile in(path, "mesh file", UINT64_MAX);
      requireMemory(saturatingMul(in.size(), kMeshBytesPerFileByte),
                    "'" + path + "' (" + formatBytes(in.size()) + "): reading it", options.memoryLimit);
      return in.readRest();
    } catch (const std::runtime_error& e) {  // InputError, MemoryLimitError
      f.fail("file", e.what());
    }
  }

  void scaleAndTranslate(JsonFields& f, Shape& s) {
    const float scale = f.number("scale", 1.0f);
    if (!(scale > 0.0f)) f.fail("scale", "must be positive");
    const Vec3 translate = f.vec3("translate", Vec3(0.0f));
    for (Vec3& p : s.positions) p = p * scale + translate;
  }

  void loadPly(JsonFields& f, Shape& s, const std::vector<std::string>& attributes) {
    const std::string path = resolve(f.string("file"));
    const std::string bytes = readMeshFile(f, path);
    try {
      readPlyMesh(bytes, path, options.memoryLimit, s, attributes);
    } catch (const std::runtime_error& e) {
      f.fail("file", e.what());
    }
    scaleAndTranslate(f, s);
  }

  // A Mitsuba serialized file's mesh "shape_index" (core/serialized_mesh.h); returns whether the
  // file asks for face normals.
  bool loadSerialized(JsonFields& f, Shape& s) {
    const std::string path = resolve(f.string("file"));
    const int index = f.integer("shape_index", 0);
    if (index < 0) f.fail("shape_index", "must not be negative");
    const std::string bytes = readMeshFile(f, path);
    bool faceNormals = false;
    try {
      faceNormals = readSerializedMesh(bytes, path, uint64_t(index), options.memoryLimit, s);
    } catch (const std::runtime_error& e) {  // InputError, MemoryLimitError
      f.fail("file", e.what());
    }
    scaleAndTranslate(f, s);
    return faceNormals;
  }

  // Placement of triangle shapes: "transform" (after any scale/translate), then "flip_normals";
  // "flip_tex_coords" reads v as 1 − v.
  void meshPlacement(JsonFields& f, Shape& s) {
    if (f.has("transform")) transformMesh(s, f.affine("transform"));
    if (f.boolean("flip_normals", false)) flipMeshNormals(s);
    if (f.boolean("flip_tex_coords", false)) flipMeshTexCoords(s);
  }

  void rectangle(JsonFields& f, Shape& s) {
    if (f.has("corners")) {
      const json& c = f.get("corners");
      if (!c.is_array() || c.size() != 4) f.fail("corners", "expected 4 corner points in order around the rectangle");
      for (size_t i = 0; i < 4; ++i) {
        if (!c[i].is_array() || c[i].size() != 3) f.fail("corners/" + std::to_string(i), "expected [x, y, z]");
        Vec3 p;
        for (int k = 0; k < 3; ++k) {
          if (!c[i][k].is_number() || !std::isfinite(c[i][k].get<double>()))
            f.fail("corners/" + std::to_string(i), "expected 3 finite numbers");
          p[k] = c[i][k].get<float>();
        }
        s.positions.push_back(p);
      }
    } else {
      const Vec3 c = f.vec3("center"), u = f.vec3("u"), v = f.vec3("v");  // u, v: half edges
      s.positions = {c - u - v, c + u - v, c + u + v, c - u + v};
    }
    s.indices = {0, 1, 2, 0, 2, 3};
    // Corners in order get (0,0), (1,0), (1,1), (0,1).
    s.cornerUvs = {Vec2(0, 0), Vec2(1, 0), Vec2(1, 1), Vec2(0, 0), Vec2(1, 1), Vec2(0, 1)};
  }

  // A sphere: center and radius, placed by "transform" if given, which may only rotate (or
  // mirror), scale uniformly and translate; its rotation turns the sphere's own axes, in which its
  // texture coordinates are computed (Shape::sphereAxes).
  void sphere(JsonFields& f, Shape& s) {
    s.kind = Shape::Kind::Sphere;
    s.center = f.vec3("center");
    s.radius = f.number("radius");
    if (!(s.radius > 0.0f)) f.fail("radius", "must be positive");
    if (!f.has("transform")) return;
    const glm::mat4 m = f.affine("transform");
    const float scale = uniformScale(glm::mat3(m), true);
    if (!(scale > 0.0f)) f.fail("transform", "a sphere's transform may only rotate, mirror, translate and scale uniformly");
    s.center = Vec3(m * glm::vec4(s.center, 1.0f));
    s.radius *= scale;
    s.sphereAxes = glm::mat3(m) / scale;
    if (!std::isfinite(s.radius) || !std::isfinite(s.center.x) || !std::isfinite(s.center.y) || !std::isfinite(s.center.z))
      f.fail("transform", "the placed sphere lies beyond the range of a 32-bit float");
  }

  // The open cylinder from p0 to p1 (core/cylinder.h), placed by "transform" if given.
  void cylinder(JsonFields& f, Shape& s) {
    const Vec3 p0 = f.vec3("p0"), p1 = f.vec3("p1");
    const float radius = f.number("radius");
    if (!(radius > 0.0f)) f.fail("radius", "must be positive");
    if (!(glm::length(p1 - p0) > 0.0f) || !std::isfinite(glm::length(p1 - p0)))
      f.fail("p1", "must differ from p0 by a finite, non-zero length");
    glm::mat4 m = Cylinder::endsMatrix(p0, p1, radius);
    if (f.has("transform")) m = f.affine("transform") * m;
    const std::optional<Cylinder> c = Cylinder::fromMatrix(m);
    if (!c)
      f.fail(f.has("transform") ? "transform" : "radius",
             "does not keep the cylinder circular and unmirrored (it may rotate, translate, scale uniformly "
             "and stretch along the cylinder's axis)");
    if (!std::isfinite(glm::length(c->base) + c->length))
      f.fail("p0", "the cylinder is placed beyond the range of a 32-bit float");
    s.kind = Shape::Kind::Cylinder;
    s.cylinder = *c;
    s.cylinder.inward = f.boolean("flip_normals", false);
  }

  void shapes(JsonFields& root) {
    const json& arr = root.get("shapes");
    if (!arr.is_array() || arr.empty()) root.fail("shapes", "expected a non-empty array of shapes");
    for (size_t i = 0; i < arr.size(); ++i) {
      const std::string ptr = "/shapes/" + std::to_string(i);
      JsonFields f(arr[i], file, ptr);
      Shape s;
      s.name = f.string("name", "shape" + std::to_string(i));
      const std::string type = f.string("type");
      s.media = mediumInterface(f);
      // A shape with media and no material is an index-matched boundary between them.
      const std::string mat = s.media ? f.string("material", "") : f.string("material");
      if (mat.empty()) {
        s.material = kNoMaterial;
      } else {
        auto it = materialIndex.find(mat);
        if (it == materialIndex.end()) f.fail("material", "no material named '" + mat + "' in /materials");
        s.material = it->second;
      }
      // What its material's textures read: texture coordinates, mesh attributes (from PLY files).
      bool readsUv = false;
      std::vector<std::string> attributes;
      const std::vector<const Texture*> textures =
          s.isMediumBoundary() ? std::vector<const Texture*>{} : scene.materials[s.material]->textures();
      for (const Texture* t : textures) {
        readsUv = readsUv || t->readsUv();
        const std::string a = t->meshAttribute();
        if (!a.empty() && std::find(attributes.begin(), attributes.end(), a) == attributes.end()) attributes.push_back(a);
      }
      const bool ply = type == "mesh" && std::filesystem::path(f.string("file")).extension() == ".ply";
      if (!attributes.empty() && !ply)
        f.fail("material", "material '" + mat + "' reads the mesh attribute '" + attributes.front() +
                               "', which only PLY meshes carry");
      if (type == "sphere") {
        sphere(f, s);
      } else if (type == "cylinder") {
        cylinder(f, s);
      } else if (type == "mesh") {
        const std::filesystem::path extension = std::filesystem::path(f.string("file")).extension();
        bool fileAsksForFaceNormals = false;
        if (ply) loadPly(f, s, attributes);
        else if (extension == ".serialized") fileAsksForFaceNormals = loadSerialized(f, s);
        else loadObj(f, s);
        if (f.boolean("face_normals", fileAsksForFaceNormals)) s.cornerNormals.clear();
        meshPlacement(f, s);
      } else if (type == "rectangle") {
        rectangle(f, s);
        meshPlacement(f, s);
      } else if (type == "disk") {
        tessellateUnitDisk(s, kDiskSegments);
        meshPlacement(f, s);
      } else {
        f.fail("type", "unknown shape type '" + type + "' (sphere, cylinder, rectangle, mesh, disk)");
      }
      if (readsUv && !s.hasUv())
        f.fail("material", "material '" + mat + "' is textured, but this mesh has no texture coordinates (vt)");
      for (const Texture* t : textures)
        if (const MeshAttribute* a = s.attribute(t->meshAttribute()); a && a->channels != t->channels() && t->channels() == 1)
          f.fail("material", "material '" + mat + "' reads the mesh attribute '" + a->name +
                                 "' as a scalar, but it has 3 channels in this mesh");
      if (f.has("emission")) {
        if (s.isMediumBoundary()) f.fail("emission", "a medium boundary without a material cannot emit (give it a material)");
        JsonFields e(f.get("emission"), file, ptr + "/emission");
        AreaEmission em;
        em.radiance = emitterSpectrum(e, "radiance");
        em.scale = scaleField(e, em.radiance);
        em.twoSided = e.boolean("two_sided", false);
        e.finish();
        s.emission = em;
      }
      f.finish();
      s.finalize();
      // Scales and translations of finite numbers can still overflow a float.
      for (const Vec3& p : s.positions)
        if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
          throw InputError(file, ptr, type + " has a vertex beyond the range of a 32-bit float");
      if (!(s.area > 0.0f)) throw InputError(file, ptr, "degenerate " + type + ": total area is zero");
      if (!std::isfinite(s.area)) throw InputError(file, ptr, type + " is too large: its area overflows a 32-bit float");
      // Different media on the two sides need a surface that separates them: a closed one. A
      // mesh file with openings (scanned models often have some) is taken as Mitsuba takes it, with
      // a note: a path changes medium where it crosses a triangle, by the side it leaves
      // (Scene::mediumBeyond), and keeps its medium through an opening.
      if (s.media && s.media->interior != s.media->exterior && !s.closed()) {
        const std::string field = ptr + (f.has("interior") ? "/interior" : "/exterior");
        if (type != "mesh")
          throw InputError(file, field,
                           "shape '" + s.name + "' is not closed (" + type +
                               " with an edge that is not shared by exactly two triangles), so it cannot separate "
                               "its interior medium from its exterior");
        if (options.notes)
          *options.notes << "kasha: note: " << file << ": " << field << ": shape '" << s.name << "' is not closed ("
                         << s.openEdges()
                         << " edges are not shared by exactly two triangles): a path changes medium where it "
                            "crosses a triangle, and keeps its medium through an opening\n";
      }
      scene.shapes.push_back(std::move(s));
    }
  }

  // The image file a light casts (a projector's "image", a spot's "texture"), in linear sRGB with row
  // 0 at the top; "encoding" "srgb" (the default) or "linear".
  RgbImage lightImage(JsonFields& f, const std::string& key) {
    const std::string encoding = f.string("encoding", "srgb");
    if (encoding != "srgb" && encoding != "linear") f.fail("encoding", "'" + encoding + "' is not srgb or linear");
    RgbImage image;
    try {
      const std::string path = resolve(f.string(key));
      const auto t = textures.load(path, TextureChannel::Rgb, TextureWrap::Clamp, TextureFilter::Nearest,
                                   encoding == "srgb" ? TextureEncoding::Srgb : TextureEncoding::Linear);
      requireMemory(saturatingMul(uint64_t(t->width()) * uint64_t(t->height()), kEmittingImageBytesPerPixel),
                    "'" + path + "' (" + std::to_string(t->width()) + " x " + std::to_string(t->height()) + "): the light's image",
                    options.memoryLimit);
      image.width = t->width();
      image.height = t->height();
      for (int y = 0; y < image.height; ++y)  // row 0 at the top; texture v counts from the bottom
        for (int x = 0; x < image.width; ++x)
          image.pixels.push_back(t->rgb(Vec2((float(x) + 0.5f) / float(image.width), 1.0f - (float(y) + 0.5f) / float(image.height))));
    } catch (const std::runtime_error& e) {
      f.fail(key, e.what());
    }
    return image;
  }

  // A spot light (core/light.h): "cone_angle", "falloff_start", "intensity", "scale", and optionally
  // a "texture" (an image file, "encoding" as a projector's) oriented by "up" (default [0, 1, 0]).
  std::unique_ptr<Light> spot(JsonFields& f) {
    const Vec3 p = f.vec3("position");
    const Vec3 at = f.vec3("look_at");
    if (!(glm::length(at - p) > 0.0f)) f.fail("look_at", "equals the position");
    const float cone = f.number("cone_angle");
    if (!(cone > 0.0f && cone <= 90.0f)) f.fail("cone_angle", "must be in (0, 90] degrees");
    const float falloff = f.number("falloff_start", cone);
    if (!(falloff > 0.0f && falloff <= cone)) f.fail("falloff_start", "must be in (0, cone_angle] degrees");
    Spectrum I = emitterSpectrum(f, "intensity");
    const float scale = scaleField(f, I);
    if (!f.has("texture")) {
      for (const char* key : {"up", "encoding"})
        if (f.has(key)) f.fail(key, "orients or decodes a spot's texture; give it with a \"texture\"");
      return std::make_unique<SpotLight>(p, at - p, cone, falloff, std::move(I), scale);
    }
    if (!(cone < 90.0f)) f.fail("cone_angle", "a textured spot's cone must be narrower than 90 degrees");
    const Vec3 up = f.vec3("up", Vec3(0, 1, 0));
    if (!(glm::length(glm::cross(up, glm::normalize(at - p))) > 1e-6f)) f.fail("up", "is parallel to the spot's axis");
    const RgbImage image = lightImage(f, "texture");
    try {
      return std::make_unique<SpotLight>(p, at - p, cone, falloff, std::move(I), scale, &image, up);
    } catch (const std::runtime_error& e) {
      f.fail("texture", e.what());
    }
  }

  // A projector (core/projector_light.h): "image" (a file; "encoding" "srgb", the default, or
  // "linear") or "irradiance" (an RGB colour), "fov" across the image's width, "scale".
  std::unique_ptr<Light> projector(JsonFields& f) {
    const Vec3 p = f.vec3("position"), at = f.vec3("look_at"), up = f.vec3("up", Vec3(0, 1, 0));
    if (!(glm::length(at - p) > 0.0f)) f.fail("look_at", "equals the position");
    if (!(glm::length(glm::cross(up, glm::normalize(at - p))) > 1e-6f)) f.fail("up", "is parallel to the projection");
    const float fov = f.number("fov");
    if (!(fov > 0.0f && fov < 180.0f)) f.fail("fov", "horizontal field of view must be in (0, 180) degrees");
    const float scale = f.number("scale", 1.0f);
    if (!(scale > 0.0f)) f.fail("scale", "must be positive");
    if (f.has("image") == f.has("irradiance")) f.fail("image", "give either image (a file) or irradiance (an RGB colour)");
    RgbImage image;
    if (f.has("irradiance")) {
      const json& c = f.get("irradiance");
      if (!c.is_array() || c.size() != 3) f.fail("irradiance", "expected [r, g, b] (linear sRGB)");
      Vec3 rgb;
      for (int k = 0; k < 3; ++k) {
        if (!c[size_t(k)].is_number() || !(c[size_t(k)].get<float>() >= 0.0f)) f.fail("irradiance", "expected 3 numbers ≥ 0");
        rgb[k] = c[size_t(k)].get<float>();
      }
      image = RgbImage{1, 1, {rgb}};
    } else {
      image = lightImage(f, "image");
    }
    try {
      return std::make_unique<ProjectorLight>(p, at, up, fov, image, scale, scene.range);
    } catch (const std::runtime_error& e) {
      f.fail(f.has("image") ? "image" : "irradiance", e.what());
    }
  }

  void lights(JsonFields& root) {
    const SceneBounds bounds = scene.accel->bounds();
    if (root.has("lights")) {
      const json& arr = root.get("lights");
      if (!arr.is_array()) root.fail("lights", "expected an array of lights");
      for (size_t i = 0; i < arr.size(); ++i) {
        const std::string ptr = "/lights/" + std::to_string(i);
        JsonFields f(arr[i], file, ptr);
        const std::string type = f.string("type");
        std::unique_ptr<Light> l;
        // Lights inside the scene may sit in a medium; distant and environment light comes from outside it.
        const bool placed = type == "point" || type == "spot" || type == "projector";
        const int medium = placed && f.has("medium") ? mediumNamed(f.string("medium"), file, f.path("medium")) : -1;
        if (type == "point") {
          const Vec3 p = f.vec3("position");
          Spectrum I = emitterSpectrum(f, "intensity");
          const float scale = scaleField(f, I);
          l = std::make_unique<PointLight>(p, std::move(I), scale);
        } else if (type == "spot") {
          l = spot(f);
        } else if (type == "projector") {
          l = projector(f);
        } else if (type == "distant") {
          const Vec3 d = f.vec3("direction");
          if (!(glm::length(d) > 0.0f)) f.fail("direction", "must not be zero");
          Spectrum E = emitterSpectrum(f, "irradiance");
          const float scale = scaleField(f, E);
          l = std::make_unique<DistantLight>(d, std::move(E), scale, bounds);
        } else if (type == "environment") {
          if (scene.environmentLight >= 0) f.fail("type", "only one environment light is allowed");
          Spectrum L = emitterSpectrum(f, "radiance");
          const float scale = scaleField(f, L);
          scene.environmentLight = int(scene.lights.size());
          l = std::make_unique<EnvironmentLight>(std::move(L), scale, bounds);
        } else if (type == "envmap") {
          if (scene.environmentLight >= 0) f.fail("type", "only one environment light is allowed");
          const std::string path = resolve(f.string("file"));
          const float scale = f.number("scale", 1.0f);
          if (!(scale > 0.0f)) f.fail("scale", "must be positive");
          const glm::mat4 m = f.has("transform") ? f.affine("transform") : glm::mat4(1.0f);
          if (!(uniformScale(glm::mat3(m)) > 0.0f)) f.fail("transform", "must rotate only (and scale uniformly)");
          scene.environmentLight = int(scene.lights.size());
          try {
            l = std::make_unique<EnvMapLight>(loadEnvironmentImage(path, options.memoryLimit), m, scale, bounds, scene.range);
          } catch (const std::runtime_error& e) {
            f.fail("file", e.what());
          }
        } else {
          f.fail("type", "unknown light type '" + type + "' (point, spot, projector, distant, environment, envmap)");
        }
        f.finish();
        scene.lights.push_back(std::move(l));
        scene.lightMedium.push_back(medium);
      }
    }
    scene.shapeLight.assign(scene.shapes.size(), -1);
    for (size_t i = 0; i < scene.shapes.size(); ++i)
      if (scene.shapes[i].emission) {
        scene.shapeLight[i] = int(scene.lights.size());
        scene.lights.push_back(std::make_unique<AreaLight>(scene.shapes[i]));
        // Its shape's MediumInterface, if any, says which medium each side emits into.
        scene.lightMedium.push_back(scene.shapes[i].media ? scene.shapes[i].media->exterior : -1);
      }
    if (scene.lights.empty()) throw InputError(file, "/lights", "the scene has no light (no light and no emissive shape)");
    // Power = spectrum · scale · a geometric factor (area, 4π, ...): finite factors can still
    // overflow, and an infinite power would turn every light choice into NaN.
    const size_t listed = scene.lights.size() - size_t(std::count_if(scene.shapes.begin(), scene.shapes.end(),
                                                                      [](const Shape& sh) { return bool(sh.emission); }));
    float total = 0.0f;
    for (size_t i = 0; i < scene.lights.size(); ++i) {
      const Light& l = *scene.lights[i];
      const float power = l.powerFactor() * l.scale() * l.spectrum().integral(scene.range);
      total += power;
      if (std::isfinite(power) && std::isfinite(total)) continue;
      std::string where = "/lights/" + std::to_string(i);
      if (i >= listed)
        for (size_t k = 0; k < scene.shapeLight.size(); ++k)
          if (scene.shapeLight[k] == int(i)) where = "/shapes/" + std::to_string(k) + "/emission";
      throw InputError(file, where, std::isfinite(power) ? "the lights' total power overflows a 32-bit float"
                                                         : "the emitted power overflows a 32-bit float");
    }
    scene.lightSelector = std::make_unique<LightSelector>(scene.lights);
  }
};

// Every number is used as a 32-bit float: one finite as a double but beyond ±3.4e38 would
// silently become infinite.
void checkFloatRange(const json& v, const std::string& file, const std::string& ptr, int depth = 0) {
  if (depth > kMaxJsonDepth)
    throw InputError(file, ptr, nestedDeeperThan(kMaxJsonDepth));
  if (v.is_number_float() && !std::isfinite(float(v.get<double>())))
    throw InputError(file, ptr, "number " + v.dump() + " is out of range of a 32-bit float");
  if (v.is_object())
    for (auto it = v.begin(); it != v.end(); ++it) checkFloatRange(it.value(), file, ptr + "/" + it.key(), depth + 1);
  if (v.is_array())
    for (size_t i = 0; i < v.size(); ++i) checkFloatRange(v[i], file, ptr + "/" + std::to_string(i), depth + 1);
}

}  // namespace

std::unique_ptr<Scene> loadSceneFromString(const std::string& text, const std::string& path,
                                           const SceneLoadOptions& options) {
  if (mitsuba::isMitsubaScenePath(path)) return mitsuba::loadMitsubaScene(text, path, options);
  return loadSceneFromJson(parseJsonStrict(text, path), path, options);
}

std::unique_ptr<Scene> loadSceneFromJson(const nlohmann::json& original, const std::string& path,
                                         const SceneLoadOptions& options) {
  nlohmann::json edited;
  if (!options.renderSettings.empty()) {
    edited = original;
    applyRenderSettings(edited, options.renderSettings, path);
  }
  const nlohmann::json& root = options.renderSettings.empty() ? original : edited;
  checkFloatRange(root, path, "");
  auto scene = std::make_unique<Scene>();
  scene->path = path;
  Loader L(path, *scene, options);
  JsonFields f(root, path, "");
  L.range(f);
  L.render(f);
  L.camera(f);
  L.spectra(f);
  L.materials(f);
  L.media(f);
  L.shapes(f);
  scene->accel = std::make_unique<Accel>(scene->shapes);
  L.lights(f);
  f.string("description", "");
  f.finish();
  checkMediumAssignments(*scene, path);
  return scene;
}

std::string readSceneFile(const std::string& path) { return readInputFile(path, "scene file", kMaxJsonFileBytes); }

std::unique_ptr<Scene> loadScene(const std::string& path, const SceneLoadOptions& options) {
  return loadSceneFromString(readSceneFile(path), path, options);
}

}  // namespace kasha
