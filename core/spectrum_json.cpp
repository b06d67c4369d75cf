#include "core/spectrum_json.h"

#include <cmath>
#include <cstdio>

#include "core/error.h"
#include "core/json_fields.h"
#include "core/rgb_spectrum.h"
#include "core/spectrum_csv.h"
#include "core/spectrum_presets.h"

namespace kasha {
namespace {

std::string formatNm(float nm) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", double(nm));
  return buf;
}

std::string presetList() {
  std::string s;
  for (const std::string& n : presetNames()) s += (s.empty() ? "" : ", ") + n;
  return s;
}

float nonNegative(JsonFields& f, const std::string& key, float fallback, bool required) {
  const float v = required ? f.number(key) : f.number(key, fallback);
  if (v < 0.0f) f.fail(key, "must not be negative (" + std::to_string(v) + ")");
  return v;
}

// A linear sRGB reflectance colour: three numbers in [0, 1].
Vec3 rgbField(JsonFields& f, const std::string& key) {
  const nlohmann::json& v = f.get(key);
  if (!v.is_array() || v.size() != 3) f.fail(key, "expected [r, g, b] (linear sRGB, each in [0, 1])");
  Vec3 rgb;
  for (int i = 0; i < 3; ++i) {
    if (!v[i].is_number()) f.fail(key + "/" + std::to_string(i), "expected a number, got " + jsonTypeName(v[i]));
    rgb[i] = v[i].get<float>();
    if (!(rgb[i] >= 0.0f && rgb[i] <= 1.0f))
      f.fail(key + "/" + std::to_string(i), "reflectance colour component " + std::to_string(rgb[i]) + " is outside [0, 1]");
  }
  return rgb;
}

Spectrum parseObject(const nlohmann::json& v, const SpectrumContext& ctx, const std::string& ptr) {
  JsonFields f(v, ctx.file, ptr);
  const std::string type = f.string("type");
  Spectrum s;
  if (type == "constant") {
    s = Spectrum::constant(nonNegative(f, "value", 0.0f, true));
  } else if (type == "tabulated") {
    const nlohmann::json& wl = f.get("wavelengths");
    const nlohmann::json& val = f.get("values");
    if (!wl.is_array() || wl.empty()) f.fail("wavelengths", "expected a non-empty array of numbers");
    if (!val.is_array() || val.size() != wl.size())
      f.fail("values", "expected an array of numbers as long as /wavelengths (" + std::to_string(wl.size()) + ")");
    std::vector<float> x, y;
    for (size_t i = 0; i < wl.size(); ++i) {
      const std::string wi = "wavelengths/" + std::to_string(i), vi = "values/" + std::to_string(i);
      if (!wl[i].is_number() || !std::isfinite(wl[i].get<double>())) f.fail(wi, "expected a finite number");
      if (!val[i].is_number() || !std::isfinite(val[i].get<double>())) f.fail(vi, "expected a finite number");
      if (!(wl[i].get<float>() > 0.0f)) f.fail(wi, "wavelength must be positive (" + wl[i].dump() + ")");
      if (!x.empty() && wl[i].get<float>() <= x.back()) f.fail(wi, "wavelengths must be strictly increasing");
      if (val[i].get<float>() < 0.0f) f.fail(vi, "negative value " + std::to_string(val[i].get<float>()));
      x.push_back(wl[i].get<float>());
      y.push_back(val[i].get<float>());
    }
    s = Spectrum::piecewiseLinear(x, y);
  } else if (type == "file") {
    const std::string rel = f.string("file");
    const std::string path = ctx.resolve(rel);
    const bool explicitOutside = f.has("outside");
    const std::string outside = f.string("outside", "clamp");
    if (outside != "clamp" && outside != "zero") f.fail("outside", "expected \"clamp\" or \"zero\", got \"" + outside + "\"");
    const std::string column = f.string("column", "");
    SpectralTable table;
    try {
      table = readSpectralCsv(path);
      s = spectrumFromTable(table, column);
    } catch (const InputError& e) {
      throw InputError(ctx.file, ptr, e.what());
    }
    if (ctx.range) {
      // Data from elsewhere often stops short of the scene's range: extending it silently would
      // invent values, so the scene has to say how (or the range has to shrink).
      const float lo = table.lambdas.front(), hi = table.lambdas.back();
      const WavelengthRange& r = *ctx.range;
      const std::string covers = path + " covers " + formatNm(lo) + "-" + formatNm(hi) + " nm";
      const std::string scene = "the scene's wavelength range " + formatNm(r.min) + "-" + formatNm(r.max) + " nm";
      if (hi <= r.min || lo >= r.max) throw InputError(ctx.file, ptr, covers + ", outside " + scene);
      if ((lo > r.min || hi < r.max) && !explicitOutside)
        throw InputError(ctx.file, ptr, covers + ", less than " + scene +
                                            ": add \"outside\": \"clamp\" (continue its end values) or \"zero\"");
    }
    if (outside == "zero") s = s.zeroOutside();
  } else if (type == "gaussian") {
    const float centre = f.number("center");
    const float fwhm = f.number("fwhm");
    if (!(fwhm > 0.0f)) f.fail("fwhm", "must be positive");
    if (!(centre > 0.0f)) f.fail("center", "must be a positive wavelength");
    s = Spectrum::gaussian(centre, fwhm, nonNegative(f, "peak", 1.0f, false));
  } else if (type == "blackbody") {
    const float k = f.number("kelvin");
    if (!(k > 0.0f)) f.fail("kelvin", "must be positive");
    s = Spectrum::blackbody(k);
  } else if (type == "box") {
    const float lo = f.number("min"), hi = f.number("max");
    if (lo < 0.0f) f.fail("min", "wavelength must not be negative (" + formatNm(lo) + ")");
    if (!(hi > lo)) f.fail("max", "must exceed /min");
    s = Spectrum::box(lo, hi, nonNegative(f, "value", 1.0f, false));
  } else if (type == "rgb") {
    s = rgbToSpectrum(rgbField(f, "value"), ctx.range ? *ctx.range : WavelengthRange{});
  } else if (type == "preset") {
    const std::string name = f.string("name");
    const auto p = presetSpectrum(name);
    if (!p) f.fail("name", "unknown preset '" + name + "' (known: " + presetList() + ")");
    s = *p;
  } else {
    f.fail("type", "unknown spectrum type '" + type +
                       "' (constant, tabulated, file, gaussian, blackbody, box, rgb, preset)");
  }
  // A value that overflows before the scale is applied is the type's field's fault (a blackbody of
  // 10^30 K), not the scale's.
  for (float y : s.values())
    if (!std::isfinite(y))
      f.fail(type == "blackbody" ? "kelvin" : type == "gaussian" ? "peak" : "type",
             "the " + type + " spectrum overflows a 32-bit float");
  const float scale = nonNegative(f, "scale", 1.0f, false);
  f.finish();
  if (scale != 1.0f) s = s.scaled(scale);
  for (float y : s.values())
    if (!std::isfinite(y)) f.fail("scale", "the scaled spectrum overflows a 32-bit float");
  return s;
}

}  // namespace

Spectrum parseSpectrum(const nlohmann::json& v, const SpectrumContext& ctx, const std::string& ptr) {
  if (v.is_number()) {
    const double d = v.get<double>();
    if (!std::isfinite(d)) throw InputError(ctx.file, ptr, "spectrum value is not finite");
    if (d < 0.0) throw InputError(ctx.file, ptr, "spectrum value must not be negative (" + std::to_string(d) + ")");
    return Spectrum::constant(float(d));
  }
  if (v.is_string()) {
    const std::string name = v.get<std::string>();
    if (ctx.resolveName)
      if (const Spectrum* s = ctx.resolveName(name, ptr)) return *s;
    if (ctx.named) {
      auto it = ctx.named->find(name);
      if (it != ctx.named->end()) return it->second;
    }
    if (auto p = presetSpectrum(name)) return *p;
    throw InputError(ctx.file, ptr, "unknown spectrum '" + name + "' (not in /spectra; presets: " + presetList() + ")");
  }
  if (v.is_object()) return parseObject(v, ctx, ptr);
  throw InputError(ctx.file, ptr, "expected a spectrum (number, name or object), got " + jsonTypeName(v));
}

}  // namespace kasha
