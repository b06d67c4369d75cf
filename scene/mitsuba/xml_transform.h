#pragma once
// Mitsuba's <transform> element: a sequence of <translate>, <rotate>, <scale>, <matrix> and
// <lookat>, each applied after the previous ones (M = T_n ··· T_2 · T_1), as an affine 4×4 matrix.
#include <glm/mat4x4.hpp>
#include <nlohmann/json.hpp>

#include "core/math.h"
#include "scene/mitsuba/xml_plugin.h"

namespace kasha::mitsuba {

using Mat4 = glm::mat4;  // column-major (glm): M[column][row]

// The matrix of a <transform> element (identity for an empty node).
Mat4 parseTransform(XmlImport& xml, pugi::xml_node transform);
// A 3-vector attribute such as origin="0, 0, 1" or a <point>/<vector> property's value.
Vec3 parseVec3(XmlImport& xml, pugi::xml_node n, const char* attribute);
// A <point>/<vector> property: x/y/z attributes or value="x, y, z".
Vec3 parsePointProperty(XmlImport& xml, pugi::xml_node p);

// The "transform" field of kasha's scene JSON: four rows of four numbers.
nlohmann::json matrixJson(const Mat4& m);
// The to_world <transform> property of a plugin, identity if absent.
Mat4 toWorld(Plugin& p);

inline Vec3 transformPoint(const Mat4& m, const Vec3& p) { return Vec3(m * glm::vec4(p, 1.0f)); }
inline Vec3 transformVector(const Mat4& m, const Vec3& v) { return Vec3(m * glm::vec4(v, 0.0f)); }

}  // namespace kasha::mitsuba
