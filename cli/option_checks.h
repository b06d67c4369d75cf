#pragma once
// Checks of option values shared by the subcommands, with short messages (CLI11's own print the
// range up to DBL_MAX, and let NaN and infinity through).
#include <CLI/CLI.hpp>

#include <cmath>

#include "core/number_check.h"

namespace kasha {

// A number keeping `rule` (the render's own in integrators/render_numbers.h).
CLI::Validator numberCheck(const NumberRule& rule);
CLI::Validator numberCheck(Sign sign, bool integer, double max = HUGE_VAL);
// A value `parse` accepts; its std::invalid_argument is the message.
CLI::Validator parseCheck(void (*parse)(const std::string&), const std::string& name);
// One of integratorNames() (integrators/integrator_factory.h).
extern const CLI::Validator kIntegratorName;
// A byte size such as 512M or 8G (core/memory_budget.h).
extern const CLI::Validator kByteSize;

}  // namespace kasha
