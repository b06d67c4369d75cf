#include "cli/option_checks.h"

#include <algorithm>
#include <cstdlib>
#include <stdexcept>

#include "core/memory_budget.h"
#include "integrators/integrator_factory.h"

namespace kasha {

CLI::Validator numberCheck(const NumberRule& rule) {
  return CLI::Validator(
      [=](std::string& v) {
        char* end = nullptr;
        const double d = std::strtod(v.c_str(), &end);
        return numberProblem(end == v.c_str() || *end != '\0' ? NAN : d, v, rule);
      },
      rule.integer ? (rule.sign == Sign::Positive ? "INT>0" : "INT>=0")
                   : (rule.sign == Sign::Positive ? "NUMBER>0" : rule.sign == Sign::NonNegative ? "NUMBER>=0" : "NUMBER"));
}

CLI::Validator numberCheck(Sign sign, bool integer, double max) { return numberCheck(NumberRule{sign, integer, max}); }

const CLI::Validator kIntegratorName([](std::string& v) { return integratorNameError(v); }, "INTEGRATOR");

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
