#include "scene/mitsuba/xml_medium.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/spectrum_json.h"
#include "core/volume_grid.h"
#include "scene/mitsuba/xml_spectrum.h"
#include "scene/mitsuba/xml_transform.h"

namespace kasha::mitsuba {
namespace {

using nlohmann::json;

// k·s for kasha spectrum JSON s: a number, or an object form with its optional "scale".
json scaled(const json& s, double k) {
  if (s.is_number()) return s.get<double>() * k;
  json out = s;
  out["scale"] = s.value("scale", 1.0) * k;
  return out;
}

// The spectrum kasha's loader makes of `s`, for the products below; errors at the element `at`.
Spectrum parsed(XmlImport& xml, pugi::xml_node at, const json& s) {
  try {
    return parseSpectrum(s, SpectrumContext(xml.where(at), xml.baseDir(at)), "");
  } catch (const InputError& e) {
    xml.fail(at, e.reason());
  }
}

// σ_t(λ)·w(λ)·scale with w = α (scattering) or 1 − α (absorption), tabulated: exact at the knots
// of both spectra and, where both vary, at least every nanometre between them (the product of two
// piecewise-linear functions is quadratic between knots; up to 64 points per interval). At a step
// (a repeated knot) the left value at the knot and the right one just after it. Both constant: a
// number.
json productSpectrum(const Spectrum& sigmaT, const Spectrum& albedo, bool scattering, double scale) {
  const auto value = [&](float sigma, float a) { return double(sigma) * (scattering ? a : 1.0 - a) * scale; };
  std::vector<float> knots;
  for (const Spectrum* s : {&sigmaT, &albedo})
    for (float x : s->lambdas())
      if (x > 0.0f) knots.push_back(x);
  std::sort(knots.begin(), knots.end());
  knots.erase(std::unique(knots.begin(), knots.end()), knots.end());
  if (knots.empty()) return value(sigmaT(550.0f), albedo(550.0f));
  const bool bothVary = sigmaT.lambdas().size() > 1 && albedo.lambdas().size() > 1;
  std::vector<float> wavelengths;
  std::vector<double> values;
  const auto add = [&](float x, float sigma, float a) {
    if (!wavelengths.empty() && x <= wavelengths.back()) return;  // strictly increasing knots
    wavelengths.push_back(x);
    values.push_back(value(sigma, a));
  };
  for (size_t i = 0; i < knots.size(); ++i) {
    const float x = knots[i];
    add(x, sigmaT.leftLimit(x), albedo.leftLimit(x));
    if (sigmaT.leftLimit(x) != sigmaT(x) || albedo.leftLimit(x) != albedo(x))
      add(std::nextafter(x, 2.0f * x), sigmaT(x), albedo(x));  // a step: its right value just after it
    if (bothVary && i + 1 < knots.size()) {
      const int steps = int(std::min(std::ceil(knots[i + 1] - x), 64.0f));  // ≤ 1 nm, ≤ 64 per interval
      for (int k = 1; k < steps; ++k) {
        const float between = x + (knots[i + 1] - x) * float(k) / float(steps);
        add(between, sigmaT(between), albedo(between));
      }
    }
  }
  return {{"type", "tabulated"}, {"wavelengths", wavelengths}, {"values", values}};
}

// What a `gridvolume` may become where a medium reads it (docs/mitsuba-import.md): a heterogeneous
// medium's σ_t grid becomes kasha's density, a homogeneous medium's albedo grid its albedo_grid.
enum class GridRole { None, Density, Albedo };

// A property that Mitsuba reads as a volume (a spectrum, or a <volume> plugin): a spectrum, or a
// `constvolume`'s. A `gridvolume` is taken where `role` allows it: it is written to `grid`
// (placed as Mitsuba places it) and the property is 1.
json volumeProperty(Plugin& m, const std::string& name, double fallback, GridRole role, json& grid) {
  XmlImport& xml = m.xml();
  const pugi::xml_node p = m.property(name);
  if (!p) return fallback;
  if (std::string(p.name()) != "volume") return spectrumElement(xml, p);
  Plugin v(xml, p);
  json out = 1.0;
  if (v.type() == "constvolume") {
    out = spectrumProperty(v, "value");
  } else if (v.type() == "gridvolume") {
    if (role == GridRole::None)
      v.fail("a spatially varying " + name + " is not supported here (kasha takes a grid as a heterogeneous medium's "
             "sigma_t or a homogeneous medium's albedo)");
    if (!v.has("filename")) v.fail("missing property 'filename'");
    grid = {{"file", xml.resolve(p, v.string("filename", ""))}, {"use_grid_bbox", v.boolean("use_grid_bbox", false)},
            {"transform", matrixJson(toWorld(v))}};
    const std::string filter = v.string("filter_type", "trilinear");
    if (filter != "trilinear") v.fail(v.property("filter_type"), "filter_type '" + filter + "': kasha interpolates grids trilinearly only");
    const std::string wrap = v.string("wrap_mode", "clamp");
    if (role == GridRole::Albedo) {
      if (!gridWrapNamed(wrap)) v.fail(v.property("wrap_mode"), "wrap_mode '" + wrap + "' is not clamp, repeat or mirror");
      grid["wrap_mode"] = wrap;
      // Mitsuba upsamples a colour grid unless raw (its own docs: no plugin needs raw colours).
      if (v.boolean("raw", false)) v.fail(v.property("raw"), "raw = true: kasha upsamples an albedo grid's colours");
    } else {
      if (wrap != "clamp") v.fail(v.property("wrap_mode"), "wrap_mode '" + wrap + "': kasha clamps density lookups to the grid's box");
      v.boolean("raw", false);  // how colour grids are upsampled: a density has one channel
    }
    v.boolean("accel", true);  // GPU texture hardware in Mitsuba: no effect on the image
  } else {
    v.fail("unsupported volume plugin (constvolume; gridvolume as a heterogeneous medium's sigma_t or a homogeneous "
           "medium's albedo)");
  }
  v.finish();
  return out;
}

// The phase function's g: Mitsuba's default is isotropic (g = 0); `hg` defaults to g = 0.8.
float phaseAsymmetry(Plugin& m) {
  const std::vector<pugi::xml_node> phases = m.nested("phase");
  if (phases.empty()) return 0.0f;
  if (phases.size() > 1) m.fail(phases[1], "more than one phase function");
  Plugin p(m.xml(), phases[0]);
  float g = 0.0f;
  if (p.type() == "hg") g = p.number("g", 0.8f);
  else if (p.type() != "isotropic") p.fail("unsupported phase plugin (isotropic, hg)");
  p.finish();
  return g;
}

// kasha's fluorophores (materials/medium_json.h) from <fluorophore> elements: sigma_f (scaled
// by the medium's `scale`, like every coefficient per unit length) or molar_absorption with
// concentration (the medium's length_unit converts them), emission, yield.
json fluorophores(Plugin& m, double scale) {
  json list = json::array();
  for (pugi::xml_node node : m.nested("fluorophore")) {
    Plugin f(m.xml(), node);
    json fl = json::object();
    if (f.has("sigma_f")) fl["sigma_f"] = scaled(spectrumProperty(f, "sigma_f"), scale);
    if (f.has("molar_absorption")) {
      fl["molar_absorption"] = spectrumProperty(f, "molar_absorption");
      fl["concentration"] = f.number("concentration");
    }
    fl["emission"] = spectrumProperty(f, "emission", nullptr, SpectrumUse::Emission);
    fl["yield"] = f.number("yield");
    f.finish();
    list.push_back(std::move(fl));
  }
  if (list.empty()) m.fail("a fluorescent_homogeneous medium needs at least one <fluorophore>");
  return list;
}

}  // namespace

std::string addMedium(XmlImport& xml, pugi::xml_node node, SceneJson& out) {
  Plugin m(xml, node);
  const std::string& type = m.type();
  if (type != "homogeneous" && type != "heterogeneous" && type != "fluorescent_homogeneous")
    m.fail("unsupported medium plugin (homogeneous, heterogeneous; kasha's fluorescent_homogeneous)");
  const float scale = m.number("scale", 1.0f);
  if (!(scale >= 0.0f)) m.fail(m.property("scale"), "scale must not be negative");
  json density, albedoGrid;
  json sigmaT = volumeProperty(m, "sigma_t", 1.0, type == "heterogeneous" ? GridRole::Density : GridRole::None, density);
  const json albedo =
      volumeProperty(m, "albedo", 0.75, type == "homogeneous" ? GridRole::Albedo : GridRole::None, albedoGrid);
  const pugi::xml_node albedoAt = m.property("albedo") ? m.property("albedo") : node;
  json medium = {{"type", density.is_null() ? "homogeneous" : "heterogeneous"}};
  if (!density.is_null()) medium["density"] = density;
  // σ_a = σ_t(1 − α)·scale, σ_s = σ_t·α·scale (Mitsuba 3 docs: homogeneous; src/media/homogeneous.cpp).
  if (!albedoGrid.is_null()) {  // α varies in space: σ_t·scale, split at each point (media.md §7)
    medium["albedo_grid"] = albedoGrid;
    medium["sigma_t"] = scaled(sigmaT, scale);
  } else if (albedo.is_number()) {
    const double a = albedo.get<double>();
    if (!(a >= 0.0 && a <= 1.0)) m.fail(albedoAt, "albedo must lie in [0, 1]");
    medium["sigma_a"] = scaled(sigmaT, (1.0 - a) * scale);
    medium["sigma_s"] = scaled(sigmaT, a * scale);
  } else {
    const Spectrum a = parsed(xml, albedoAt, albedo);
    if (a.minimum() < 0.0f || a.maxValue(0.0f, 1e30f) > 1.0f) m.fail(albedoAt, "albedo must lie in [0, 1]");
    const Spectrum s = parsed(xml, m.property("sigma_t") ? m.property("sigma_t") : node, sigmaT);
    medium["sigma_a"] = productSpectrum(s, a, false, scale);
    medium["sigma_s"] = productSpectrum(s, a, true, scale);
  }
  medium["g"] = phaseAsymmetry(m);
  if (type == "fluorescent_homogeneous") {
    medium["fluorophores"] = fluorophores(m, scale);
    const std::string unit = m.string("length_unit", "");
    if (!unit.empty()) medium["length_unit"] = unit;
  }
  if (!m.boolean("sample_emitters", true))
    m.note("sample_emitters = false ignored: kasha samples lights from inside media too (the same image, other noise)");
  if (!m.boolean("has_spectral_extinction", true))
    m.note("has_spectral_extinction = false ignored: kasha tracks the extinction at each wavelength (the same image "
           "where sigma_t does not vary with wavelength)");
  m.finish();
  const std::string id = node.attribute("id") ? xml.attribute(node, "id") : "";
  const std::string base = id.empty() ? xml.label(node) : id;
  std::string name = base;
  for (int k = 2; out.root["media"].contains(name); ++k) name = base + "#" + std::to_string(k);
  out.root["media"][name] = std::move(medium);
  out.origin("/media/" + name, xml, node);
  if (!id.empty()) out.mediumIds[id] = name;
  return name;
}

std::optional<std::string> mediumOf(XmlImport& xml, pugi::xml_node n, SceneJson& out) {
  const std::string tag = n.name();
  if (tag == "medium") return addMedium(xml, n, out);
  if (tag != "ref") return std::nullopt;
  const auto it = out.mediumIds.find(xml.attribute(n, "id"));
  if (it == out.mediumIds.end()) return std::nullopt;
  return it->second;
}

std::optional<std::string> endpointMedium(Plugin& endpoint, SceneJson& out, std::vector<pugi::xml_node>& otherRefs) {
  std::vector<pugi::xml_node> found = endpoint.nested("medium");
  for (pugi::xml_node r : endpoint.nested("ref")) {
    if (out.mediumIds.count(endpoint.xml().attribute(r, "id"))) found.push_back(r);
    else otherRefs.push_back(r);
  }
  if (found.empty()) return std::nullopt;
  if (found.size() > 1) endpoint.fail(found[1], "more than one medium (an endpoint sits in one)");
  return mediumOf(endpoint.xml(), found[0], out);
}

}  // namespace kasha::mitsuba
