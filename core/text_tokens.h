#pragma once
// The tokens of a line of a text format whose fields are separated by spaces and tabs: OBJ (as
// tinyobjloader splits it) and PLY. Any other byte, a control character included, is part of a
// token, so a checker that refuses odd tokens refuses odd separators too.
#include <string_view>
#include <vector>

namespace kasha {

std::vector<std::string_view> spaceSeparatedTokens(std::string_view line);

}  // namespace kasha
