#include "scene/mitsuba/xml_transform.h"

#include <glm/gtc/matrix_transform.hpp>

#include <string>

namespace kasha::mitsuba {
namespace {

// x/y/z attributes (each defaulting to `fallback`) or one value="..." of 1 or 3 numbers.
Vec3 componentsOrValue(XmlImport& xml, pugi::xml_node n, float fallback) {
  if (const auto value = xml.optionalAttribute(n, "value")) {
    if (n.attribute("x") || n.attribute("y") || n.attribute("z"))
      xml.fail(n, "give either 'value' or 'x'/'y'/'z', not both");
    const auto v = parseNumbers(*value);
    if (v && v->size() == 3) return {(*v)[0], (*v)[1], (*v)[2]};
    if (v && v->size() == 1) return Vec3((*v)[0]);
    xml.fail(n, "value '" + *value + "' is not 1 or 3 finite numbers");
  }
  Vec3 r(fallback);
  const char* names[3] = {"x", "y", "z"};
  for (int k = 0; k < 3; ++k)
    if (const auto s = xml.optionalAttribute(n, names[k])) {
      const auto v = parseNumbers(*s);
      if (!v || v->size() != 1) xml.fail(n, std::string("'") + names[k] + "' = '" + *s + "' is not a finite number");
      r[k] = v->front();
    }
  return r;
}

// Mitsuba's look-at frame: the camera's z towards the target, y up, x = up × z (its "left").
Mat4 lookAt(XmlImport& xml, pugi::xml_node n) {
  const Vec3 origin = parseVec3(xml, n, "origin"), target = parseVec3(xml, n, "target");
  const Vec3 up = n.attribute("up") ? parseVec3(xml, n, "up") : Vec3(0, 1, 0);
  const Vec3 d = target - origin;
  if (!(glm::length(d) > 0.0f)) xml.fail(n, "origin and target are the same point");
  const Vec3 dir = glm::normalize(d);
  const Vec3 l = glm::cross(up, dir);
  if (!(glm::length(l) > 1e-6f * glm::length(up))) xml.fail(n, "'up' is parallel to the viewing direction (or zero)");
  const Vec3 left = glm::normalize(l), newUp = glm::cross(dir, left);
  Mat4 m(1.0f);
  m[0] = glm::vec4(left, 0.0f);
  m[1] = glm::vec4(newUp, 0.0f);
  m[2] = glm::vec4(dir, 0.0f);
  m[3] = glm::vec4(origin, 1.0f);
  return m;
}

}  // namespace

Vec3 parseVec3(XmlImport& xml, pugi::xml_node n, const char* attribute) {
  const std::string text = xml.attribute(n, attribute);
  const auto v = parseNumbers(text);
  if (!v || v->size() != 3) xml.fail(n, std::string("'") + attribute + "' = '" + text + "' is not 3 finite numbers");
  return {(*v)[0], (*v)[1], (*v)[2]};
}

Vec3 parsePointProperty(XmlImport& xml, pugi::xml_node p) {
  const std::string tag = p.name();
  if (tag != "point" && tag != "vector") xml.fail(p, "expected <point> or <vector>, got <" + tag + ">");
  return componentsOrValue(xml, p, 0.0f);
}

nlohmann::json matrixJson(const Mat4& m) {
  nlohmann::json rows = nlohmann::json::array();
  for (int r = 0; r < 4; ++r) rows.push_back({m[0][r], m[1][r], m[2][r], m[3][r]});
  return rows;
}

Mat4 toWorld(Plugin& p) {
  const pugi::xml_node t = p.property("to_world");
  if (!t) return Mat4(1.0f);
  if (std::string(t.name()) != "transform") p.fail(t, "to_world must be a <transform>");
  return parseTransform(p.xml(), t);
}

Mat4 parseTransform(XmlImport& xml, pugi::xml_node transform) {
  Mat4 m(1.0f);
  for (pugi::xml_node op : transform.children()) {
    if (op.type() != pugi::node_element) continue;
    const std::string tag = op.name();
    Mat4 t(1.0f);
    if (tag == "translate") {
      t = glm::translate(Mat4(1.0f), componentsOrValue(xml, op, 0.0f));
    } else if (tag == "scale") {
      const Vec3 s = componentsOrValue(xml, op, 1.0f);
      if (s.x == 0.0f || s.y == 0.0f || s.z == 0.0f) xml.fail(op, "a scale of zero makes the transform singular");
      t = glm::scale(Mat4(1.0f), s);
    } else if (tag == "rotate") {
      const Vec3 axis = componentsOrValue(xml, op, 0.0f);
      if (!(glm::length(axis) > 0.0f)) xml.fail(op, "the rotation axis is zero");
      const auto angle = parseNumbers(xml.attribute(op, "angle"));
      if (!angle || angle->size() != 1) xml.fail(op, "'angle' is not a finite number (degrees)");
      t = glm::rotate(Mat4(1.0f), glm::radians(angle->front()), glm::normalize(axis));
    } else if (tag == "matrix") {
      const std::string text = xml.attribute(op, "value");
      const auto v = parseNumbers(text);
      if (!v || (v->size() != 16 && v->size() != 9)) xml.fail(op, "value is not 16 (or 9) finite numbers");
      const int n = v->size() == 16 ? 4 : 3;
      for (int r = 0; r < n; ++r)
        for (int c = 0; c < n; ++c) t[c][r] = (*v)[size_t(r * n + c)];  // given row by row
      if (n == 4 && (t[0][3] != 0.0f || t[1][3] != 0.0f || t[2][3] != 0.0f || t[3][3] != 1.0f))
        xml.fail(op, "the last row must be 0 0 0 1: kasha takes affine transforms only");
      if (glm::determinant(Mat4(t)) == 0.0f) xml.fail(op, "the matrix is singular");
    } else if (tag == "lookat") {
      t = lookAt(xml, op);
    } else {
      xml.fail(op, "unsupported transform operation <" + tag + "> (translate, rotate, scale, matrix, lookat)");
    }
    m = t * m;
  }
  return m;
}

}  // namespace kasha::mitsuba
