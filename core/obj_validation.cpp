#include "core/obj_validation.h"

#include <charconv>
#include <cmath>
#include <cstdint>
#include <string_view>
#include <vector>

#include "core/error.h"
#include "core/text_tokens.h"

namespace kasha {
namespace {

// Whether the whole token is a number finite as a 32-bit float.
bool finiteFloat(std::string_view t) {
  if (!t.empty() && t[0] == '+') t.remove_prefix(1);
  double v = 0.0;
  const auto r = std::from_chars(t.data(), t.data() + t.size(), v);
  return !t.empty() && r.ec == std::errc() && r.ptr == t.data() + t.size() && std::isfinite(v) &&
         std::isfinite(float(v));
}

struct Counts {
  int64_t v = 0, vt = 0, vn = 0;
};

class Checker {
 public:
  Checker(const std::string& path) : path_(path) {}

  // Checks one line (without its comment).
  void line(std::string_view text, int64_t number) {
    where_ = path_ + ":" + std::to_string(number);
    const std::vector<std::string_view> t = spaceSeparatedTokens(text);
    if (t.empty()) return;
    const std::string_view key = t[0];
    if (key == "v") numbers(t, {3, 4, 6, 7}, counts_.v);
    else if (key == "vt") numbers(t, {1, 2, 3}, counts_.vt);
    else if (key == "vn") numbers(t, {3}, counts_.vn);
    else if (key == "f") corners(t, 3, "a face");
    else if (key == "l") corners(t, 2, "a line");
    else if (key == "p") corners(t, 1, "a point");
  }

 private:
  [[noreturn]] void fail(const std::string& reason) const { throw InputError(where_, "", reason); }

  void numbers(const std::vector<std::string_view>& t, std::initializer_list<size_t> allowed, int64_t& count) {
    const size_t n = t.size() - 1;
    bool ok = false;
    for (const size_t a : allowed) ok = ok || n == a;
    if (!ok) {
      std::string list;
      for (const size_t a : allowed) list += (list.empty() ? "" : " or ") + std::to_string(a);
      fail("'" + std::string(t[0]) + "' takes " + list + " numbers, found " + std::to_string(n));
    }
    for (size_t i = 1; i < t.size(); ++i)
      if (!finiteFloat(t[i]))
        fail("'" + std::string(t[i]) + "' is not a finite number (" + std::string(t[0]) + " component " +
             std::to_string(i) + ")");
    ++count;
  }

  // One index of a corner: an integer, not 0, within the `defined` elements so far.
  void index(std::string_view text, int64_t defined, const char* kind, const char* kinds, std::string_view corner) {
    int64_t i = 0;
    const auto r = std::from_chars(text.data(), text.data() + text.size(), i);
    if (text.empty() || r.ec != std::errc() || r.ptr != text.data() + text.size())
      fail("corner '" + std::string(corner) + "': '" + std::string(text) + "' is not an integer index");
    if (i == 0 || i > defined || i < -defined)
      fail("corner '" + std::string(corner) + "' refers to " + kind + " " + std::string(text) + ", but " +
           std::to_string(defined) + " " + (defined == 1 ? std::string(kind) + " is" : std::string(kinds) + " are") +
           " defined before this line");
  }

  void corners(const std::vector<std::string_view>& t, size_t minimum, const char* what) {
    if (t.size() - 1 < minimum)
      fail(std::string(what) + " needs at least " + std::to_string(minimum) + " corners, found " + std::to_string(t.size() - 1));
    for (size_t k = 1; k < t.size(); ++k) {
      const std::string_view c = t[k];
      const size_t s1 = c.find('/');
      const size_t s2 = s1 == std::string_view::npos ? std::string_view::npos : c.find('/', s1 + 1);
      if (s2 != std::string_view::npos && c.find('/', s2 + 1) != std::string_view::npos)
        fail("corner '" + std::string(c) + "' has more than three indices");
      index(c.substr(0, s1), counts_.v, "vertex", "vertices", c);
      if (s1 == std::string_view::npos) continue;
      const std::string_view vt = c.substr(s1 + 1, s2 == std::string_view::npos ? std::string_view::npos : s2 - s1 - 1);
      if (!vt.empty() || s2 == std::string_view::npos) index(vt, counts_.vt, "texture coordinate", "texture coordinates", c);
      if (s2 != std::string_view::npos) index(c.substr(s2 + 1), counts_.vn, "normal", "normals", c);
    }
  }

  std::string path_, where_;
  Counts counts_;
};

}  // namespace

std::string validateObjText(const std::string& text, const std::string& path) {
  Checker check(path);
  std::string uncommented;
  uncommented.reserve(text.size());
  // Lines end at "\n", "\r\n" or a lone "\r", as tinyobjloader reads them.
  std::string_view rest(text);
  int64_t number = 0;
  while (!rest.empty()) {
    const size_t end = rest.find_first_of("\r\n");
    std::string_view content = rest.substr(0, end);
    if (const size_t hash = content.find('#'); hash != std::string_view::npos) content = content.substr(0, hash);
    check.line(content, ++number);
    uncommented += content;
    if (end == std::string_view::npos) break;
    const bool crlf = rest[end] == '\r' && end + 1 < rest.size() && rest[end + 1] == '\n';
    uncommented += rest.substr(end, crlf ? 2 : 1);
    rest.remove_prefix(end + (crlf ? 2 : 1));
  }
  return uncommented;
}

}  // namespace kasha
