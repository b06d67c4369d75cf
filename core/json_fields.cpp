#include "core/json_fields.h"

#include <glm/mat3x3.hpp>
#include <glm/matrix.hpp>

#include <climits>
#include <cmath>

namespace kasha {

std::string jsonTypeName(const nlohmann::json& v) { return v.type_name(); }

JsonFields::JsonFields(const nlohmann::json& obj, std::string file, std::string pointer)
    : obj_(obj), file_(std::move(file)), pointer_(std::move(pointer)) {
  if (!obj_.is_object()) throw InputError(file_, pointer_.empty() ? "/" : pointer_, "expected an object, got " + jsonTypeName(obj_));
}

void JsonFields::fail(const std::string& key, const std::string& reason) const {
  throw InputError(file_, path(key), reason);
}

const nlohmann::json& JsonFields::get(const std::string& key) {
  if (!obj_.contains(key)) fail(key, "missing required field");
  used_.insert(key);
  return obj_.at(key);
}

float JsonFields::number(const std::string& key) {
  const nlohmann::json& v = get(key);
  if (!v.is_number()) fail(key, "expected a number, got " + jsonTypeName(v));
  const double d = v.get<double>();
  if (!std::isfinite(d)) fail(key, "number is not finite");
  return float(d);
}

float JsonFields::number(const std::string& key, float fallback) { return has(key) ? number(key) : fallback; }

int JsonFields::integer(const std::string& key, int fallback) { return has(key) ? integer(key) : fallback; }

int JsonFields::integer(const std::string& key) {
  const nlohmann::json& v = get(key);
  if (!v.is_number_integer()) fail(key, "expected an integer, got " + jsonTypeName(v));
  const bool fits = v.is_number_unsigned() ? v.get<uint64_t>() <= uint64_t(INT_MAX)
                                           : v.get<int64_t>() >= INT_MIN && v.get<int64_t>() <= INT_MAX;
  if (!fits) fail(key, "integer " + v.dump() + " is out of range");
  return v.get<int>();
}

bool JsonFields::boolean(const std::string& key, bool fallback) {
  if (!has(key)) return fallback;
  const nlohmann::json& v = get(key);
  if (!v.is_boolean()) fail(key, "expected true or false, got " + jsonTypeName(v));
  return v.get<bool>();
}

std::string JsonFields::string(const std::string& key) {
  const nlohmann::json& v = get(key);
  if (!v.is_string()) fail(key, "expected a string, got " + jsonTypeName(v));
  return v.get<std::string>();
}

std::string JsonFields::string(const std::string& key, const std::string& fallback) {
  return has(key) ? string(key) : fallback;
}

Vec3 JsonFields::vec3(const std::string& key) {
  const nlohmann::json& v = get(key);
  if (!v.is_array() || v.size() != 3) fail(key, "expected an array of 3 numbers");
  Vec3 r;
  for (int i = 0; i < 3; ++i) {
    if (!v[i].is_number() || !std::isfinite(v[i].get<double>())) fail(key, "expected an array of 3 finite numbers");
    r[i] = v[i].get<float>();
  }
  return r;
}

Vec3 JsonFields::vec3(const std::string& key, Vec3 fallback) { return has(key) ? vec3(key) : fallback; }

void JsonFields::finish() const {
  for (auto it = obj_.begin(); it != obj_.end(); ++it)
    if (!used_.count(it.key())) throw InputError(file_, path(it.key()), "unknown field");
}

glm::mat4 JsonFields::affine(const std::string& key) {
  const nlohmann::json& rows = get(key);
  glm::mat4 m(1.0f);
  if (!rows.is_array() || rows.size() != 4) fail(key, "expected 4 rows of 4 numbers");
  for (size_t r = 0; r < 4; ++r) {
    if (!rows[r].is_array() || rows[r].size() != 4) fail(key, "expected 4 rows of 4 numbers");
    for (size_t c = 0; c < 4; ++c) {
      if (!rows[r][c].is_number() || !std::isfinite(rows[r][c].get<double>())) fail(key, "expected finite numbers");
      m[int(c)][int(r)] = rows[r][c].get<float>();
    }
  }
  if (m[0][3] != 0.0f || m[1][3] != 0.0f || m[2][3] != 0.0f || m[3][3] != 1.0f)
    fail(key, "the last row must be [0, 0, 0, 1] (an affine map)");
  if (glm::determinant(glm::mat3(m)) == 0.0f) fail(key, "the matrix is singular");
  return m;
}

}  // namespace kasha
