#include "cli/option_checks.h"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <stdexcept>

#include "core/memory_budget.h"
#include "integrators/integrator_factory.h"

namespace kasha {

CLI::Validator numberCheck(Sign sign, bool integer, double max) {
  return CLI::Validator(
      [=](std::string& v) {
        char* end = nullptr;
        const double d = std::strtod(v.c_str(), &end);
        if (end == v.c_str() || *end != '\0' || !std::isfinite(d))
          return "expected a finite " + std::string(integer ? "integer" : "number") + ", got '" + v + "'";
        if (integer && d != std::floor(d)) return "expected an integer, got '" + v + "'";
        if (sign == Sign::NonNegative && d < 0.0) return "must not be negative, got '" + v + "'";
        if (sign == Sign::Positive && !(d > 0.0)) return "must be positive, got '" + v + "'";
        if (d > max) {
          char limit[32];
          std::snprintf(limit, sizeof limit, "%.10g", max);
          return "must be at most " + std::string(limit) + ", got '" + v + "'";
        }
        return std::string();
      },
      integer ? (sign == Sign::Positive ? "INT>0" : "INT>=0") : (sign == Sign::Positive ? "NUMBER>0" : sign == Sign::NonNegative ? "NUMBER>=0" : "NUMBER"));
}

const CLI::Validator kIntegratorName(
    [](std::string& v) {
      const std::vector<std::string> names = integratorNames();
      if (std::find(names.begin(), names.end(), v) != names.end()) return std::string();
      for (const IntegratorAlias& alias : integratorAliases())
        if (alias.name == v) return std::string();
      std::string list;
      for (const std::string& n : names) list += (list.empty() ? "" : ", ") + n;
      return "unknown integrator '" + v + "' (" + list + ")";
    },
    "INTEGRATOR");

CLI::Validator parseCheck(void (*parse)(const std::string&), const std::string& name) {
  return CLI::Validator(
      [parse](std::string& v) {
        try {
          parse(v);
          return std::string();
        } catch (const std::invalid_argument& e) {
          return std::string(e.what());
        }
      },
      name);
}

const CLI::Validator kByteSize = parseCheck([](const std::string& v) { parseByteSize(v); }, "BYTES");

}  // namespace kasha
