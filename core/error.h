#pragma once
// Errors that blame the user's input: every one names where (file, line or field) and why.
#include <stdexcept>
#include <string>

namespace kasha {

// "where: field: reason" — where is a file (optionally with ":line"), field a JSON pointer or
// column name; either may be empty.
class InputError : public std::runtime_error {
 public:
  InputError(const std::string& where, const std::string& field, const std::string& reason)
      : std::runtime_error(compose(where, field, reason)) {}

 private:
  static std::string compose(const std::string& where, const std::string& field,
                             const std::string& reason) {
    std::string s = where;
    if (!field.empty()) s += (s.empty() ? "" : ": ") + field;
    return s + (s.empty() ? "" : ": ") + reason;
  }
};

}  // namespace kasha
