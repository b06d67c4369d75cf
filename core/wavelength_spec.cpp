#include "core/wavelength_spec.h"

#include <cmath>
#include <stdexcept>

namespace kasha {
namespace {

const char* const kKinds[] = {"uniform", "cmf", "light", "absorption", "emission", "yamamoto", "material", "event"};
const char* const kCombinations[] = {"mix", "os-power", "ms-balance", "ms-power"};

float parseNumber(const std::string& s, const std::string& what, const std::string& text) {
  size_t used = 0;
  float v = 0.0f;
  try {
    v = std::stof(s, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used != s.size() || s.empty() || !std::isfinite(v))
    throw std::invalid_argument("wavelength strategy '" + text + "': " + what + " '" + s + "' is not a number");
  return v;
}

WavelengthSpec::Component parseComponent(std::string s, bool inCombination, const std::string& text) {
  WavelengthSpec::Component c;
  if (const size_t at = s.find('@'); at != std::string::npos) {
    if (!inCombination)
      throw std::invalid_argument("wavelength strategy '" + text + "': a weight '@' needs a combination (mix:…)");
    c.weight = parseNumber(s.substr(at + 1), "weight", text);
    if (!(c.weight > 0.0f)) throw std::invalid_argument("wavelength strategy '" + text + "': weights must be positive");
    s.resize(at);
  }
  std::string wf;
  const size_t eq = s.find('=');
  if (eq != std::string::npos) {
    wf = s.substr(eq + 1);
    s.resize(eq);
  }
  bool found = false;
  for (int k = 0; k < 8; ++k)
    if (s == kKinds[k]) c.kind = WavelengthSpec::Kind(k), found = true;
  if (!found)
    throw std::invalid_argument("wavelength strategy '" + text + "': unknown kind '" + s +
                                "' (uniform | cmf | light | absorption | emission | yamamoto | material | event)");
  if (eq != std::string::npos) {
    if (c.kind != WavelengthSpec::Kind::Yamamoto)
      throw std::invalid_argument("wavelength strategy '" + text + "': only yamamoto takes a value (yamamoto=w_F)");
    c.yamamotoWF = parseNumber(wf, "w_F", text);
    if (!(c.yamamotoWF >= 0.0f && c.yamamotoWF <= 1.0f))
      throw std::invalid_argument("wavelength strategy '" + text + "': w_F must lie in [0, 1]");
  }
  return c;
}

}  // namespace

bool WavelengthSpec::uses(Kind k) const {
  for (const Component& c : components)
    if (c.kind == k) return true;
  return false;
}

const char* toString(WavelengthSpec::Kind k) { return kKinds[int(k)]; }

WavelengthSpec parseWavelengthSpec(const std::string& text) {
  WavelengthSpec spec;
  spec.text = text;
  std::string list = text;
  if (const size_t colon = text.find(':'); colon != std::string::npos) {
    const std::string head = text.substr(0, colon);
    bool found = false;
    for (int k = 0; k < 4; ++k)
      if (head == kCombinations[k]) spec.combination = WavelengthSpec::Combination(k + 1), found = true;
    if (!found)
      throw std::invalid_argument("wavelength strategy '" + text + "': unknown combination '" + head +
                                  "' (mix | os-power | ms-balance | ms-power)");
    list = text.substr(colon + 1);
  }
  const bool combined = spec.combination != WavelengthSpec::Combination::Single;
  size_t start = 0;
  while (true) {
    const size_t comma = list.find(',', start);
    const std::string part = list.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
    if (part.empty()) throw std::invalid_argument("wavelength strategy '" + text + "': empty component");
    spec.components.push_back(parseComponent(part, combined, text));
    if (comma == std::string::npos) break;
    if (!combined) throw std::invalid_argument("wavelength strategy '" + text + "': a list needs a combination (mix:…)");
    start = comma + 1;
  }
  for (WavelengthSpec::Kind k : {WavelengthSpec::Kind::Material, WavelengthSpec::Kind::Event})
    if (spec.uses(k) && spec.components.size() > 1)
      throw std::invalid_argument("wavelength strategy '" + text + "': '" + toString(k) +
                                  "' cannot be combined with others");
  if (combined && spec.components.size() < 2)
    throw std::invalid_argument("wavelength strategy '" + text + "': a combination needs at least two components");
  return spec;
}

}  // namespace kasha
