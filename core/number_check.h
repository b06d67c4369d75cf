#pragma once
// The rule of a number a user gives a front end (an option of `kasha`, a keyword argument of the
// Python module) and the one check of it: both front ends refuse the same values with the same
// words. Scene files have their own checks (core/json_fields.h).
#include <cmath>
#include <string>

namespace kasha {

enum class Sign { Any, NonNegative, Positive };

struct NumberRule {
  Sign sign = Sign::Any;
  bool integer = false;
  double max = HUGE_VAL;
};

// Why `value` breaks `rule` ("must be positive, got '-3'"), quoting `text`, the value as the user
// wrote it; empty if it keeps the rule. NaN stands for text that is not a number at all.
std::string numberProblem(double value, const std::string& text, const NumberRule& rule);

}  // namespace kasha
