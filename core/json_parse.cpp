#include "core/json_parse.h"

#include <set>
#include <vector>

#include "core/error.h"

namespace kasha {
namespace {

// The keys seen in each open object and the pointer of each open value, maintained by the
// parser callback (nlohmann::json::parser_callback_t).
struct KeyTracker {
  struct Level {
    std::string pointer;
    std::set<std::string> keys;  // objects
    size_t next = 0;             // arrays: index of the next element
    bool isArray = false;
  };
  std::vector<Level> stack;
  std::string pendingKey;
  const std::string& path;

  explicit KeyTracker(const std::string& p) : path(p) {}

  // The pointer of the value about to start inside the innermost container.
  std::string childPointer() {
    if (stack.empty()) return "";
    Level& top = stack.back();
    return top.pointer + "/" + (top.isArray ? std::to_string(top.next) : pendingKey);
  }

  bool operator()(int depth, nlohmann::json::parse_event_t event, nlohmann::json& parsed) {
    using E = nlohmann::json::parse_event_t;
    if (depth > kMaxJsonDepth)
      throw InputError(path, childPointer(), nestedDeeperThan(kMaxJsonDepth));
    switch (event) {
      case E::object_start:
      case E::array_start:
        stack.push_back({childPointer(), {}, 0, event == E::array_start});
        break;
      case E::key: {
        pendingKey = parsed.get<std::string>();
        if (!stack.back().keys.insert(pendingKey).second)
          throw InputError(path, childPointer(), "duplicate key '" + pendingKey + "' (a key may appear once in an object)");
        break;
      }
      case E::object_end:
      case E::array_end:
        stack.pop_back();
        if (!stack.empty() && stack.back().isArray) ++stack.back().next;
        break;
      case E::value:
        if (!stack.empty() && stack.back().isArray) ++stack.back().next;
        break;
    }
    return true;
  }
};

}  // namespace

nlohmann::json parseJsonStrict(const std::string& text, const std::string& path) {
  KeyTracker tracker(path);
  try {
    return nlohmann::json::parse(text, [&tracker](int depth, nlohmann::json::parse_event_t event, nlohmann::json& parsed) {
      return tracker(depth, event, parsed);
    });
  } catch (const nlohmann::json::exception& e) {  // parse_error, or out_of_range for a number like 1e400
    throw InputError(path, "", std::string("malformed JSON: ") + e.what());
  }
}

}  // namespace kasha
