#pragma once
// A strict check of Wavefront OBJ text before tinyobjloader parses it. tinyobjloader reads what
// it cannot parse as 0 ("v nan 1 0" is (0, 1, 0), "v a b c" the origin) and wraps face indices
// beyond its int range, so geometry would change silently; this pass refuses such files instead.
// Checked, line by line as tinyobjloader splits them (at "\n", "\r\n" or "\r"; tokens separated
// by spaces and tabs; a '#' starts a comment that runs to the end of the line, also after data):
//   v x y z [w | r g b [a]]   3, 4, 6 or 7 numbers;  vt u [v [w]]   1 to 3;  vn x y z   3;
//   every number parsed to its end and finite as a 32-bit float;
//   f (3 or more), l (2 or more), p (1 or more) corners v, v/vt, v//vn or v/vt/vn: integers,
//   not 0, referring to an element defined before the line (negative: counted back from the last).
// Other statements (o, g, s, usemtl, mtllib, ...) are left to tinyobjloader.
// tinyobjloader itself takes a '#' only at the start of a line ("f 1 2 3# 21" is a face with a
// corner 21), so it must parse the returned text, in which every comment is already removed.
#include <string>

namespace kasha {

// The text without comments, or InputError "path:line: what is wrong" for the first problem.
std::string validateObjText(const std::string& text, const std::string& path);

}  // namespace kasha
