#pragma once
// Errors that blame the user's input: every one names where (file, line or field) and why.
#include <stdexcept>
#include <string>

namespace kasha {

// `text` safe to print on a terminal: every control character (C0, DEL, and C1 in its UTF-8 form
// U+0080–U+009F) and every byte that is not part of well-formed UTF-8 becomes \xHH, so that text
// quoted from a file (an id, a file name, a value) cannot move the cursor, ring the bell or send an
// escape sequence (ECMA-48 control functions) and a message stays one line. Applying it twice
// changes nothing.
std::string printable(const std::string& text);

// The reason of every nesting limit's error (JSON, Mitsuba XML): "nested deeper than N levels".
inline std::string nestedDeeperThan(int levels) { return "nested deeper than " + std::to_string(levels) + " levels"; }

// "where: field: reason" — where is a file (optionally with ":line"), field a JSON pointer or
// column name; either may be empty. The message is printable(): parts quoted from files may hold
// any bytes.
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
    return printable(s + (s.empty() ? "" : ": ") + reason);
  }
};

// A mistake on the command line (an option's value, a combination of options, an output path):
// `kasha` exits with code 2 for these, 1 for other InputErrors. `where` is the option.
class UsageError : public InputError {
 public:
  using InputError::InputError;
};

}  // namespace kasha
