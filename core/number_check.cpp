#include "core/number_check.h"

#include <cstdio>

namespace kasha {

std::string numberProblem(double value, const std::string& text, const NumberRule& rule) {
  const std::string got = ", got '" + text + "'";
  if (!std::isfinite(value)) return std::string("expected a finite ") + (rule.integer ? "integer" : "number") + got;
  if (rule.integer && value != std::floor(value)) return "expected an integer" + got;
  if (rule.sign == Sign::NonNegative && value < 0.0) return "must not be negative" + got;
  if (rule.sign == Sign::Positive && !(value > 0.0)) return "must be positive" + got;
  if (value > rule.max) {
    char limit[32];
    std::snprintf(limit, sizeof limit, "%.10g", rule.max);
    return "must be at most " + std::string(limit) + got;
  }
  return {};
}

}  // namespace kasha
