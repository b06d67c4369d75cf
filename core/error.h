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
      : std::runtime_error(compose(where, field, reason)), field_(field), reason_(reason) {}
  // The parts of the message: a front end that gave the field's value names its own option instead
  // (`kasha render --set`, docs/cli.md).
  const std::string& field() const { return field_; }
  const std::string& reason() const { return reason_; }

 private:
  std::string field_, reason_;

  static std::string compose(const std::string& where, const std::string& field,
                             const std::string& reason) {
    std::string s = where;
    if (!field.empty()) s += (s.empty() ? "" : ": ") + field;
    return s + (s.empty() ? "" : ": ") + reason;
  }
};

// A mistake on the command line (an option's value, a combination of options, an output path):
// `kasha` exits with code 2 for these, 1 for other InputErrors. `where` is the option.
class UsageError : public InputError {
 public:
  using InputError::InputError;
};

}  // namespace kasha
