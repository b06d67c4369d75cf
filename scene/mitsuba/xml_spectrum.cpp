#include "scene/mitsuba/xml_spectrum.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include "core/input_file.h"
#include "core/rgb_illuminant.h"

namespace kasha::mitsuba {
namespace {

using nlohmann::json;

json tabulated(XmlImport& xml, pugi::xml_node p, std::vector<float> wl, std::vector<float> v) {
  if (wl.empty() || wl.size() != v.size()) xml.fail(p, "expected as many wavelengths as values, and at least one");
  for (size_t i = 1; i < wl.size(); ++i)
    if (!(wl[i] > wl[i - 1])) xml.fail(p, "wavelengths must increase strictly");
  return {{"type", "tabulated"}, {"wavelengths", wl}, {"values", v}};
}

// value="400:0.1, 500:0.3" (wavelength:value pairs).
json pairs(XmlImport& xml, pugi::xml_node p, const std::string& text) {
  std::vector<float> wl, v;
  size_t start = 0;
  while (start <= text.size()) {
    size_t end = text.find(',', start);
    if (end == std::string::npos) end = text.size();
    const std::string item = text.substr(start, end - start);
    const size_t colon = item.find(':');
    const auto a = parseNumbers(item.substr(0, colon == std::string::npos ? 0 : colon));
    const auto b = colon == std::string::npos ? std::nullopt : parseNumbers(item.substr(colon + 1));
    if (!a || !b || a->size() != 1 || b->size() != 1)
      xml.fail(p, "'" + item + "' is not a wavelength:value pair of finite numbers");
    wl.push_back(a->front());
    v.push_back(b->front());
    start = end + 1;
  }
  return tabulated(xml, p, std::move(wl), std::move(v));
}

// Mitsuba's .spd file: one "wavelength value" pair per line, '#' comments.
json spdFile(XmlImport& xml, pugi::xml_node p, const std::string& path) {
  std::istringstream in;
  try {
    in.str(readInputFile(path, "spectrum file", kMaxJsonFileBytes));  // regular files only, never blocks
  } catch (const std::runtime_error& e) {
    xml.fail(p, e.what());
  }
  std::vector<float> wl, v;
  std::string line;
  for (int n = 1; std::getline(in, line); ++n) {
    line = line.substr(0, line.find('#'));
    const auto nums = parseNumbers(line);
    if (nums && nums->empty()) continue;
    if (!nums || nums->size() != 2)
      throw InputError(path + ":" + std::to_string(n), "", "expected 'wavelength value' (two finite numbers)");
    wl.push_back((*nums)[0]);
    v.push_back((*nums)[1]);
  }
  if (wl.empty()) xml.fail(p, "'" + path + "' holds no spectrum");
  return tabulated(xml, p, std::move(wl), std::move(v));
}

// Mitsuba's blackbody is Planck's radiance in W·m⁻²·sr⁻¹·nm⁻¹; kasha's is normalised to 1 at its
// maximum over 300–830 nm (tabulated at whole nm), so the scale is that maximum of Planck's law.
json blackbody(XmlImport& xml, pugi::xml_node p, float kelvin) {
  if (!(kelvin > 0.0f)) xml.fail(p, "temperature must be positive (kelvin)");
  double peak = 0.0;
  for (int nm = 300; nm <= 830; ++nm) peak = std::max(peak, planckRadiance(nm, kelvin));
  return {{"type", "blackbody"}, {"kelvin", kelvin}, {"scale", peak}};
}

// <spectrum type="..."> with nested properties.
json spectrumPlugin(XmlImport& xml, pugi::xml_node p) {
  Plugin s(xml, p);
  json out;
  if (s.type() == "uniform") {
    out = s.number("value");
  } else if (s.type() == "blackbody") {
    out = blackbody(xml, p, s.number("temperature"));
  } else if (s.type() == "irregular") {
    const auto wl = parseNumbers(s.string("wavelengths", "")), v = parseNumbers(s.string("values", ""));
    if (!wl || !v) s.fail("'wavelengths' and 'values' must be lists of finite numbers");
    out = tabulated(xml, p, *wl, *v);
  } else if (s.type() == "regular") {
    const float lo = s.number("wavelength_min"), hi = s.number("wavelength_max");
    const auto v = parseNumbers(s.string("values", ""));
    if (!v || v->size() < 2 || !(hi > lo)) s.fail("needs wavelength_min < wavelength_max and at least two values");
    std::vector<float> wl;
    for (size_t i = 0; i < v->size(); ++i) wl.push_back(lo + (hi - lo) * float(i) / float(v->size() - 1));
    out = tabulated(xml, p, wl, *v);
  } else {
    s.fail("unsupported spectrum plugin (uniform, regular, irregular, blackbody)");
  }
  s.finish();
  return out;
}

// An emission of the linear sRGB colour c, tabulated: core/rgb_illuminant.h's spectrum, whose grey
// (v, v, v) is v times D65 at Y = 1.
json emissionOfColour(Vec3 c) {
  const Spectrum s = rgbIlluminantSpectrum(c, WavelengthRange{360.0f, 830.0f});
  return {{"type", "tabulated"}, {"wavelengths", s.lambdas()}, {"values", s.values()}};
}

// A single number: Mitsuba's spectral variants read it on an emitter as the D65 illuminant times
// the number (src/core/properties.cpp, get_texture_impl: a "d65" texture), as a grey <rgb>. A
// negative or overflowing one stays a number, which the JSON loader refuses.
json uniform(double v, SpectrumUse use) {
  const bool colour = use == SpectrumUse::Emission && v >= 0.0 && std::isfinite(float(v));
  return colour ? emissionOfColour(Vec3(float(v))) : json(v);
}

// <rgb value="r, g, b"> (or one value for grey), linear sRGB: a reflectance stays kasha's
// {"type": "rgb"} (the JSON loader upsamples it); an emission is tabulated here.
json rgb(XmlImport& xml, pugi::xml_node p, SpectrumUse use) {
  const auto v = parseNumbers(xml.attribute(p, "value"));
  if (!v || (v->size() != 3 && v->size() != 1)) xml.fail(p, "value is not 1 or 3 finite numbers");
  const Vec3 c = v->size() == 3 ? Vec3((*v)[0], (*v)[1], (*v)[2]) : Vec3(v->front());
  if (c.x < 0.0f || c.y < 0.0f || c.z < 0.0f) xml.fail(p, "negative colour component");
  if (use == SpectrumUse::Reflectance) return {{"type", "rgb"}, {"value", {c.x, c.y, c.z}}};
  return emissionOfColour(c);
}

}  // namespace

double planckRadiance(double nm, double kelvin) {
  constexpr double h = 6.62607015e-34, c = 2.99792458e8, k = 1.380649e-23;  // SI 2019 exact values
  const double l = nm * 1e-9;
  return 2.0 * h * c * c / std::pow(l, 5) / std::expm1(h * c / (l * k * kelvin)) * 1e-9;  // per nm
}

json spectrumElement(XmlImport& xml, pugi::xml_node p, SpectrumUse use) {
  const std::string tag = p.name();
  if (tag == "float") {
    const auto v = parseNumbers(xml.attribute(p, "value"));
    if (!v || v->size() != 1) xml.fail(p, "value is not a finite number");
    return uniform(v->front(), use);
  }
  if (tag == "blackbody") {
    // A number of kelvin, optionally followed by its unit ("6500", "6500K"), and nothing else.
    const std::string t = xml.attribute(p, "temperature");
    const size_t unit = t.find_last_not_of(" \t\n\r");
    const bool hasUnit = unit != std::string::npos && (t[unit] == 'K' || t[unit] == 'k');
    const auto v = parseNumbers(hasUnit ? t.substr(0, unit) : t);
    if (!v || v->size() != 1) xml.fail(p, "temperature '" + t + "' is not a number of kelvin (e.g. 6500 or 6500K)");
    json out = blackbody(xml, p, v->front());
    if (const auto s = xml.optionalAttribute(p, "scale")) {
      const auto sv = parseNumbers(*s);
      if (!sv || sv->size() != 1 || !(sv->front() >= 0.0f)) xml.fail(p, "scale is not a finite number >= 0");
      out["scale"] = out["scale"].get<double>() * sv->front();
    }
    return out;
  }
  if (tag == "rgb") return rgb(xml, p, use);
  if (tag == "texture" || tag == "ref")
    xml.fail(p, "textures are not supported for this property; give a <spectrum>");
  if (tag != "spectrum") xml.fail(p, "expected a spectrum (<spectrum>, <float>, <blackbody>), got <" + tag + ">");
  if (p.attribute("type")) return spectrumPlugin(xml, p);
  if (const auto file = xml.optionalAttribute(p, "filename")) {
    const std::string path = xml.resolve(p, *file);
    const std::string ext = std::filesystem::path(path).extension().string();
    if (ext == ".csv") {  // kasha extension: a column of a kasha spectrum CSV file
      json out = {{"type", "file"}, {"file", path}};
      if (const auto col = xml.optionalAttribute(p, "column")) out["column"] = *col;
      if (const auto outside = xml.optionalAttribute(p, "outside")) out["outside"] = *outside;
      return out;
    }
    return spdFile(xml, p, path);
  }
  const std::string value = xml.attribute(p, "value");
  if (value.find(':') != std::string::npos) return pairs(xml, p, value);
  const auto v = parseNumbers(value);
  if (!v || v->size() != 1) xml.fail(p, "value '" + value + "' is neither a number nor wavelength:value pairs");
  return uniform(v->front(), use);
}

json spectrumProperty(Plugin& owner, const std::string& name, const json& fallback, SpectrumUse use) {
  const pugi::xml_node p = owner.property(name);
  if (!p) {
    if (fallback.is_null()) owner.fail("missing spectrum property '" + name + "'");
    return fallback.is_number() ? uniform(fallback.get<double>(), use) : fallback;
  }
  return spectrumElement(owner.xml(), p, use);
}

}  // namespace kasha::mitsuba
