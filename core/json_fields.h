#pragma once
// Strict reading of one JSON object: every read names its JSON pointer in errors, and finish()
// rejects keys nobody asked for (a misspelt field is an error, not silently ignored).
#include <nlohmann/json.hpp>

#include <set>
#include <string>

#include "core/error.h"
#include <glm/mat4x4.hpp>

#include "core/math.h"

namespace kasha {

class JsonFields {
 public:
  // `pointer` is the JSON pointer of obj, e.g. "/materials/fitc".
  JsonFields(const nlohmann::json& obj, std::string file, std::string pointer);

  bool has(const std::string& key) const { return obj_.contains(key); }
  const nlohmann::json& get(const std::string& key);  // required
  std::string path(const std::string& key) const { return pointer_ + "/" + key; }
  [[noreturn]] void fail(const std::string& key, const std::string& reason) const;

  float number(const std::string& key);
  float number(const std::string& key, float fallback);
  int integer(const std::string& key);  // required
  int integer(const std::string& key, int fallback);
  bool boolean(const std::string& key, bool fallback);
  std::string string(const std::string& key);
  std::string string(const std::string& key, const std::string& fallback);
  Vec3 vec3(const std::string& key);
  Vec3 vec3(const std::string& key, Vec3 fallback);
  // Four rows of four finite numbers, an invertible affine map (last row 0 0 0 1).
  glm::mat4 affine(const std::string& key);
  // Throws for any key that was never read.
  void finish() const;

  const std::string& file() const { return file_; }
  const std::string& pointer() const { return pointer_; }

 private:
  const nlohmann::json& obj_;
  std::string file_, pointer_;
  std::set<std::string> used_;
};

// The JSON type name of v, for messages.
std::string jsonTypeName(const nlohmann::json& v);

}  // namespace kasha
