#include "materials/material_json.h"

#include <algorithm>
#include <filesystem>
#include <stdexcept>

#include "core/conductor_index.h"
#include "core/input_file.h"
#include "core/json_fields.h"
#include "core/json_parse.h"
#include "materials/blend.h"
#include "materials/coated_fluorescent.h"
#include "materials/dielectric.h"
#include "materials/jung_bbrrdf.h"
#include "materials/lambertian.h"
#include "materials/measured_material_json.h"
#include "materials/mirror.h"
#include "materials/normal_perturbation.h"
#include "materials/opacity_mask.h"
#include "materials/rough_conductor.h"
#include "materials/rough_dielectric.h"
#include "materials/texture_json.h"
#include "materials/thin_dielectric.h"

namespace kasha {
namespace {

Spectrum spectrumField(JsonFields& f, const std::string& key, const SpectrumContext& ctx) {
  return parseSpectrum(f.get(key), ctx, f.path(key));
}

// Reflectances above 1 create energy; reject them (issue: physical-parameter violations are errors).
// allowUnphysical: the material's "allow_unphysical": true.
void requireAlbedo(JsonFields& f, const std::string& key, const Spectrum& s, WavelengthRange range, bool allowUnphysical) {
  const float hi = s.maxValue(range.min, range.max);
  if (hi > 1.0f + 1e-6f && !allowUnphysical)
    f.fail(key, "reflectance " + std::to_string(hi) + " exceeds 1 in the wavelength range");
}

std::string presetList() {
  std::string s;
  for (const std::string& n : Ior::presetNames()) s += (s.empty() ? "" : ", ") + n;
  return s;
}

// A conductor's complex index: "eta": a metal's symbol ("Au", core/conductor_index.h), or "eta"
// and "k" as spectra; nullptr without "eta".
std::shared_ptr<const ComplexIndex> parseConductorIndex(JsonFields& f, const SpectrumContext& ctx, WavelengthRange range) {
  if (!f.has("eta")) {
    if (f.has("k")) f.fail("k", "needs \"eta\" as well");
    return nullptr;
  }
  const nlohmann::json& eta = f.get("eta");
  if (eta.is_string() && !f.has("k")) {
    const std::string symbol = eta.get<std::string>();
    std::optional<ComplexIndex> named = namedConductor(symbol);
    if (!named) {
      std::string list;
      for (const std::string& n : conductorNames()) list += (list.empty() ? "" : ", ") + n;
      f.fail("eta", "no measured index for the metal '" + symbol + "' (" + list + "); or give \"eta\" and \"k\" as spectra");
    }
    return std::make_shared<const ComplexIndex>(std::move(*named));
  }
  if (!f.has("k")) f.fail("eta", "a spectrum for eta needs \"k\" as well (or name a metal: \"eta\": \"Au\")");
  ComplexIndex index{spectrumField(f, "eta", ctx), spectrumField(f, "k", ctx)};
  if (!(index.eta.minValue(range.min, range.max) > 0.0f)) f.fail("eta", "must be positive in the wavelength range");
  if (!(index.k.minValue(range.min, range.max) >= 0.0f)) f.fail("k", "must not be negative in the wavelength range");
  return std::make_shared<const ComplexIndex>(std::move(index));
}

// A conductor's "reflectance": required without an index; with one, a factor on its Fresnel
// reflectance, 1 by default (Mitsuba's specular_reflectance).
Spectrum conductorReflectance(JsonFields& f, const SpectrumContext& ctx, WavelengthRange range, bool unphysical,
                              bool indexed) {
  if (indexed && !f.has("reflectance")) return Spectrum::constant(1.0f);
  Spectrum r = spectrumField(f, "reflectance", ctx);
  requireAlbedo(f, "reflectance", r, range, unphysical);
  return r;
}

// "ior": 1.5 | "BK7" | {"type": "cauchy", "A": .., "B": .., "C": ..} | {"type": "sellmeier", "B": [3], "C": [3]}
Ior parseIor(JsonFields& parent, const std::string& key, const SpectrumContext& ctx) {
  const nlohmann::json& v = parent.get(key);
  if (v.is_number()) return Ior::constant(parent.number(key));
  if (v.is_string()) {
    const std::string name = v.get<std::string>();
    const std::optional<Ior> p = Ior::preset(name);
    if (!p) parent.fail(key, "unknown index of refraction preset '" + name + "' (" + presetList() + ")");
    return *p;
  }
  if (!v.is_object()) parent.fail(key, "expected a number, a preset name or an object, got " + jsonTypeName(v));
  JsonFields f(v, ctx.file, parent.path(key));
  const std::string type = f.string("type");
  std::optional<Ior> ior;
  if (type == "cauchy") {
    const float a = f.number("A"), b = f.number("B"), c = f.number("C", 0.0f);
    ior = Ior::cauchy(a, b, c);
  } else if (type == "sellmeier") {
    const Vec3 b = f.vec3("B"), c = f.vec3("C");
    ior = Ior::sellmeier({b.x, b.y, b.z}, {c.x, c.y, c.z});
  } else {
    f.fail("type", "unknown index of refraction type '" + type + "' (cauchy, sellmeier)");
  }
  f.finish();
  return *ior;
}

// Material files may name further material files; no sensible chain is longer than this.
constexpr size_t kMaxMaterialFileDepth = 16;

// {"type": "file", "file": "m.json"}: a material object kept in its own file (what `kasha extract`
// writes); paths inside it are relative to that file. A file that names itself, directly or
// through others, is refused, as is a chain deeper than kMaxMaterialFileDepth.
std::unique_ptr<Material> parseMaterialFile(JsonFields& f, const SpectrumContext& ctx, WavelengthRange range) {
  const std::string rel = f.string("file");
  const std::string path = ctx.resolve(rel);
  std::error_code ec;
  const std::string canonical = std::filesystem::weakly_canonical(path, ec).string();
  const std::string key = ec ? path : canonical;
  const auto loop = std::find(ctx.materialFiles.begin(), ctx.materialFiles.end(), key);
  if (loop != ctx.materialFiles.end()) {
    std::string chain;
    for (auto it = loop; it != ctx.materialFiles.end(); ++it) chain += *it + " -> ";
    f.fail("file", "material files name each other in a cycle: " + chain + key);
  }
  if (ctx.materialFiles.size() >= kMaxMaterialFileDepth)
    f.fail("file", "material files name each other more than " + std::to_string(kMaxMaterialFileDepth) + " deep");
  nlohmann::json j;
  try {
    j = parseJsonStrict(readInputFile(path, "material file", kMaxJsonFileBytes), path);
  } catch (const InputError& e) {
    f.fail("file", e.what());
  }
  SpectrumContext inner = ctx;
  inner.file = path;
  inner.baseDir = std::filesystem::path(path).parent_path().string();
  if (inner.baseDir.empty()) inner.baseDir = ".";
  inner.materialFiles.push_back(key);
  return parseMaterial(j, inner, "", range);
}

// The fields of Jung18's BBRRDF, checked against eq. 8's conditions.
JungParams parseJungParams(JsonFields& f, const SpectrumContext& ctx, WavelengthRange range, bool unphysical) {
  JungParams p;
  p.absorption = spectrumField(f, "absorption", ctx);
  p.emission = spectrumField(f, "emission", ctx);
  p.reflectance = spectrumField(f, "reflectance", ctx);
  p.concentration = f.number("c");
  p.energyRatio = f.number("Q");
  p.allowUnphysical = unphysical;
  const std::string problem = checkJungParams(p, range);
  if (!problem.empty()) {
    const size_t colon = problem.find(": ");
    f.fail(problem.substr(0, colon), problem.substr(colon + 2));
  }
  return p;
}

// "reflectance_texture", "c_texture", "Q_texture" of a Jung18 base.
JungTextures parseJungTextures(JsonFields& f, const SpectrumContext& ctx) {
  return JungTextures{parseReflectanceTexture(f, "reflectance_texture", ctx), parseScalarTexture(f, "c_texture", ctx),
                      parseScalarTexture(f, "Q_texture", ctx)};
}

// "alpha": α (isotropic) | [α_x, α_y] (ggx.h)
Vec2 parseAlpha(JsonFields& f, const std::string& key) {
  const nlohmann::json& v = f.get(key);
  Vec2 a;
  if (v.is_number()) {
    a = Vec2(f.number(key));
  } else if (v.is_array() && v.size() == 2 && v[0].is_number() && v[1].is_number()) {
    a = Vec2(v[0].get<float>(), v[1].get<float>());
  } else {
    f.fail(key, "expected a roughness or an array [alpha_x, alpha_y], got " + jsonTypeName(v));
  }
  if (!(a.x >= kMinAlpha && a.x <= kMaxAlpha && a.y >= kMinAlpha && a.y <= kMaxAlpha))
    f.fail(key, "roughness must lie in [0.001, 1]");
  return a;
}

// A material nested in another (a mask's, a blend's, a perturbed normal's): one-sidedness belongs
// to the whole surface (Scene::bsdf), so only a top-level material may ask for it.
std::unique_ptr<Material> parseNestedMaterial(const nlohmann::json& v, const std::string& ptr, const SpectrumContext& ctx,
                                              WavelengthRange range) {
  std::unique_ptr<Material> nested = parseMaterial(v, ctx, ptr, range);
  if (nested->oneSided)
    throw InputError(ctx.file, ptr + "/one_sided", "only a top-level material can be one-sided (a nested one scatters as its wrapper says)");
  return nested;
}

// {"type": "normal_map", "normals": <texture>, "material": {...}} and {"type": "bump_map",
// "height": <texture>, "scale": s, "material": {...}} (normal_perturbation.h).
std::unique_ptr<Material> parsePerturbedNormal(JsonFields& f, const std::string& type, const SpectrumContext& ctx,
                                               WavelengthRange range) {
  std::unique_ptr<Material> nested = parseNestedMaterial(f.get("material"), f.path("material"), ctx, range);
  if (type == "normal_map")
    return std::make_unique<NormalMapMaterial>(std::move(nested), parseRequiredTexture(f, "normals", ctx, true));
  const float scale = f.number("scale", 1.0f);
  return std::make_unique<BumpMapMaterial>(std::move(nested), parseRequiredTexture(f, "height", ctx, false), scale);
}

// {"type": "mask", "opacity": α, "opacity_texture": <texture>, "material": {...}} (opacity_mask.h).
std::unique_ptr<Material> parseMask(JsonFields& f, const SpectrumContext& ctx, WavelengthRange range) {
  std::unique_ptr<Material> nested = parseNestedMaterial(f.get("material"), f.path("material"), ctx, range);
  if (nested->textured()) f.fail("material", "a mask around a textured material is not supported");
  const float opacity = f.number("opacity");
  if (!(opacity >= 0.0f && opacity <= 1.0f)) f.fail("opacity", "must lie in [0, 1]");
  return std::make_unique<OpacityMask>(std::move(nested), opacity, parseScalarTexture(f, "opacity_texture", ctx));
}

// {"type": "blend", "weight": w, "weight_texture": <texture>, "materials": [{...}, {...}]}
// (blend.h): (1 − w)·the first + w·the second.
std::unique_ptr<Material> parseBlend(JsonFields& f, const SpectrumContext& ctx, WavelengthRange range) {
  const nlohmann::json& list = f.get("materials");
  if (!list.is_array() || list.size() != 2)
    f.fail("materials", "expected an array of two materials, got " +
                            (list.is_array() ? std::to_string(list.size()) + " materials" : jsonTypeName(list)));
  std::unique_ptr<Material> first = parseNestedMaterial(list[0], f.path("materials") + "/0", ctx, range);
  std::unique_ptr<Material> second = parseNestedMaterial(list[1], f.path("materials") + "/1", ctx, range);
  const float weight = f.number("weight");
  if (!(weight >= 0.0f && weight <= 1.0f)) f.fail("weight", "must lie in [0, 1]");
  try {
    return std::make_unique<BlendMaterial>(std::move(first), std::move(second), weight,
                                           parseScalarTexture(f, "weight_texture", ctx));
  } catch (const std::invalid_argument& e) {
    f.fail("materials", e.what());
  }
}

}  // namespace

std::unique_ptr<Material> parseMaterial(const nlohmann::json& v, const SpectrumContext& ctx, const std::string& ptr,
                                        WavelengthRange range) {
  JsonFields f(v, ctx.file, ptr);
  const std::string type = f.string("type");
  // Physically invalid parameters (creating energy) are errors unless the scene asks for them.
  const bool unphysical = f.boolean("allow_unphysical", false);
  std::unique_ptr<Material> m;
  if (type == "lambertian") {
    Spectrum r = spectrumField(f, "reflectance", ctx);
    requireAlbedo(f, "reflectance", r, range, unphysical);
    m = std::make_unique<Lambertian>(std::move(r), parseReflectanceTexture(f, "reflectance_texture", ctx));
  } else if (type == "jung_fluorescent") {
    JungParams p = parseJungParams(f, ctx, range, unphysical);
    m = std::make_unique<JungBbrrdf>(std::move(p), range, parseJungTextures(f, ctx));
  } else if (type == "mirror") {
    std::shared_ptr<const ComplexIndex> index = parseConductorIndex(f, ctx, range);
    Spectrum r = conductorReflectance(f, ctx, range, unphysical, index != nullptr);
    m = std::make_unique<Mirror>(std::move(r), parseReflectanceTexture(f, "reflectance_texture", ctx), std::move(index));
  } else if (type == "dielectric" || type == "thin_dielectric") {
    Ior ior = parseIor(f, "ior", ctx);
    if (const std::string problem = checkIor(ior, range); !problem.empty()) f.fail("ior", problem);
    if (type == "dielectric") m = std::make_unique<Dielectric>(std::move(ior), range);
    else m = std::make_unique<ThinDielectric>(std::move(ior), range);
  } else if (type == "file") {
    m = parseMaterialFile(f, ctx, range);
  } else if (type == "zhdanov") {
    m = parseZhdanov(f, ctx, range, unphysical);
  } else if (type == "measured_reradiation") {
    m = parseMeasuredReradiation(f, ctx, range, unphysical);
  } else if (type == "rough_conductor") {
    std::shared_ptr<const ComplexIndex> index = parseConductorIndex(f, ctx, range);
    Spectrum r = conductorReflectance(f, ctx, range, unphysical, index != nullptr);
    const Vec2 a = parseAlpha(f, "alpha");
    RoughConductorTextures tex{parseReflectanceTexture(f, "reflectance_texture", ctx),
                               parseAlphaTexture(f, "alpha_texture", ctx)};
    m = std::make_unique<RoughConductor>(std::move(r), a.x, a.y, std::move(tex), std::move(index));
  } else if (type == "rough_dielectric") {
    Ior ior = parseIor(f, "ior", ctx);
    if (const std::string problem = checkIor(ior, range); !problem.empty()) f.fail("ior", problem);
    const Vec2 a = parseAlpha(f, "alpha");
    try {
      m = std::make_unique<RoughDielectric>(std::move(ior), a.x, a.y, range, parseAlphaTexture(f, "alpha_texture", ctx));
    } catch (const std::invalid_argument& e) {
      f.fail("ior", std::string(e.what()).substr(5));  // only the index can still be rejected
    }
  } else if (type == "mask") {
    m = parseMask(f, ctx, range);
  } else if (type == "blend") {
    m = parseBlend(f, ctx, range);
  } else if (type == "normal_map" || type == "bump_map") {
    m = parsePerturbedNormal(f, type, ctx, range);
  } else if (type == "coated_fluorescent") {
    JungParams p = parseJungParams(f, ctx, range, unphysical);
    Ior ior = parseIor(f, "coat_ior", ctx);
    if (const std::string problem = checkIor(ior, range); !problem.empty()) f.fail("coat_ior", problem);
    const Vec2 a = parseAlpha(f, "coat_alpha");
    CoatedTextures tex{parseJungTextures(f, ctx), parseAlphaTexture(f, "coat_alpha_texture", ctx)};
    m = std::make_unique<CoatedFluorescent>(std::move(p), std::move(ior), a.x, a.y, range, std::move(tex));
  } else {
    f.fail("type", "unknown material type '" + type +
                       "' (lambertian, jung_fluorescent, mirror, dielectric, thin_dielectric, rough_conductor, rough_dielectric, "
                       "coated_fluorescent, zhdanov, measured_reradiation, normal_map, bump_map, mask, blend, file)");
  }
  // Mitsuba's one-sided BSDFs (black from behind): Scene::bsdf restricts the surface's Bsdf.
  m->oneSided = m->oneSided || f.boolean("one_sided", false);
  f.finish();
  return m;
}

}  // namespace kasha
