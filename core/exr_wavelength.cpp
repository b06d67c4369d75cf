#include "core/exr_wavelength.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <map>

namespace kasha {
namespace {

constexpr double kSpeedOfLight = 299792458.0;  // m/s

}  // namespace

std::optional<float> parseExrWavelength(const std::string& part) {
  static const std::map<std::string, double> kPrefix = {
      {"", 1.0},    {"Y", 1e24}, {"Z", 1e21}, {"E", 1e18},  {"P", 1e15}, {"T", 1e12}, {"G", 1e9}, {"M", 1e6},
      {"k", 1e3},   {"h", 1e2},  {"da", 1e1}, {"d", 1e-1},  {"c", 1e-2}, {"m", 1e-3}, {"u", 1e-6}, {"n", 1e-9},
      {"p", 1e-12}};
  const auto digit = [&](size_t k) { return k < part.size() && std::isdigit(static_cast<unsigned char>(part[k])); };
  size_t k = 0, digits = 0;
  for (; digit(k); ++k) ++digits;
  if (k < part.size() && part[k] == ',')
    for (++k; digit(k); ++k) ++digits;
  if (digits == 0) return std::nullopt;
  if (k < part.size() && (part[k] == 'e' || part[k] == 'E')) {
    const size_t sign = k + 1 < part.size() && (part[k + 1] == '+' || part[k + 1] == '-') ? 1 : 0;
    if (digit(k + 1 + sign)) {  // otherwise E is the exa prefix
      k += 1 + sign;
      while (digit(k)) ++k;
    }
  }
  std::string value = part.substr(0, k), unit = part.substr(k);
  std::replace(value.begin(), value.end(), ',', '.');
  const bool hertz = unit.size() >= 2 && unit.compare(unit.size() - 2, 2, "Hz") == 0;
  const bool metres = !hertz && !unit.empty() && unit.back() == 'm';
  if (!hertz && !metres) return std::nullopt;
  const auto prefix = kPrefix.find(unit.substr(0, unit.size() - (hertz ? 2 : 1)));
  if (prefix == kPrefix.end()) return std::nullopt;
  const double v = std::strtod(value.c_str(), nullptr) * prefix->second;
  const double m = metres ? v : kSpeedOfLight / v;
  if (!(m > 0.0) || !std::isfinite(m)) return std::nullopt;
  return float(m * 1e9);
}

std::string exrWavelengthName(float nm) {
  std::string s = std::to_string(double(nm));
  std::replace(s.begin(), s.end(), '.', ',');
  return s + "nm";
}

}  // namespace kasha
