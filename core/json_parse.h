#pragma once
// Parsing the JSON files users write (scenes, material files): malformed text, a key given twice
// in one object (nlohmann::json would silently keep the last) and nesting deeper than
// kMaxJsonDepth are InputErrors naming the file and, for a duplicate, its JSON pointer.
#include <string>

#include <nlohmann/json.hpp>

namespace kasha {

// No valid scene nests deeper than a few levels; a limit keeps every recursion over it bounded.
constexpr int kMaxJsonDepth = 64;

nlohmann::json parseJsonStrict(const std::string& text, const std::string& path);

}  // namespace kasha
