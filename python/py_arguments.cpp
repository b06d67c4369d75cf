#include "python/py_arguments.h"

#include <cmath>
#include <stdexcept>

#include "core/error.h"
#include "core/memory_budget.h"

namespace py = pybind11;

namespace kasha::python {
namespace {

[[noreturn]] void refuse(const Argument& arg, const std::string& reason) { throw InputError(arg.function, arg.name, reason); }

std::string typeName(const py::handle& value) {
  return py::str(py::type::handle_of(value).attr("__name__")).cast<std::string>();
}

// The value as Python prints it, for messages; at most 40 characters (an int of thousands of
// digits may not even be printable).
std::string shown(const py::handle& value) {
  std::string s;
  try {
    s = py::repr(value).cast<std::string>();
  } catch (const py::error_already_set&) {
    s = "<" + typeName(value) + ">";
  }
  return s.size() > 40 ? s.substr(0, 37) + "..." : s;
}

}  // namespace

void refuseType(const Argument& arg, const char* expected, const py::handle& value) {
  refuse(arg, std::string("expected ") + expected + ", got " + typeName(value) + " " + shown(value));
}

double number(const py::handle& value, const Argument& arg, const NumberRule& rule) {
  // What float() takes, but not True (not a count) nor a str (float("3") would parse it).
  if (!PyNumber_Check(value.ptr()) || PyBool_Check(value.ptr()))
    refuseType(arg, "a number", value);
  double d = NAN;  // an int beyond a double's range: "expected a finite number"
  if (PyObject* f = PyNumber_Float(value.ptr())) {
    d = PyFloat_AsDouble(f);
    Py_DECREF(f);
  } else {
    PyErr_Clear();
  }
  if (const std::string why = numberProblem(d, shown(value), rule); !why.empty()) refuse(arg, why);
  return d;
}

int integer(const py::handle& value, const Argument& arg, const NumberRule& rule) { return int(number(value, arg, rule)); }

std::string text(const py::handle& value, const Argument& arg) {
  if (!py::isinstance<py::str>(value)) refuseType(arg, "a string", value);
  return value.cast<std::string>();
}

std::string filePath(const py::handle& value, const Argument& arg) {
  if (PyObject* fs = PyOS_FSPath(value.ptr())) {  // the str itself, or what __fspath__ returns
    const py::object name = py::reinterpret_steal<py::object>(fs);
    if (py::isinstance<py::str>(name)) return name.cast<std::string>();
  } else {
    PyErr_Clear();
  }
  refuseType(arg, "a file name (str or os.PathLike)", value);
}

bool flag(const py::handle& value, const Argument& arg) {
  if (!PyBool_Check(value.ptr())) refuseType(arg, "True or False", value);
  return value.ptr() == Py_True;
}

uint64_t byteSize(const py::handle& value, const Argument& arg) {
  try {
    return parseByteSize(text(value, arg));
  } catch (const std::invalid_argument& e) {
    refuse(arg, e.what());
  }
}

}  // namespace kasha::python
