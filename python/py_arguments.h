#pragma once
// Arguments of the Python module's functions read from Python objects by the command line's rules
// (core/number_check.h, integrators/render_numbers.h). A value of the wrong type or out of range
// raises kasha.InputError naming the function and the argument ("kasha.render: spp: must be
// positive, got '-3'"), never the TypeError of pybind11's conversions: every such argument is
// taken as a py::object and read here.
#include <pybind11/pybind11.h>

#include <cstdint>
#include <string>

#include "core/number_check.h"

namespace kasha::python {

// An argument as messages name it: the function ("kasha.render") and the keyword ("spp").
struct Argument {
  const char* function;
  const char* name;
};

// A real number (int, float, numpy scalar; not bool, str or None) keeping `rule`.
double number(const pybind11::handle& value, const Argument& arg, const NumberRule& rule);
// The same as an int; `rule` must be of integers no larger than INT_MAX.
int integer(const pybind11::handle& value, const Argument& arg, const NumberRule& rule);
// A str.
std::string text(const pybind11::handle& value, const Argument& arg);
// A file name: a str or an os.PathLike naming one (pathlib.Path).
std::string filePath(const pybind11::handle& value, const Argument& arg);
// True or False.
bool flag(const pybind11::handle& value, const Argument& arg);
// A byte size such as "512M" or "8G" (core/memory_budget.h).
uint64_t byteSize(const pybind11::handle& value, const Argument& arg);
// Raises InputError "expected <expected>, got <type> <value>".
[[noreturn]] void refuseType(const Argument& arg, const char* expected, const pybind11::handle& value);

}  // namespace kasha::python
