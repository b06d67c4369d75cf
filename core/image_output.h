#pragma once
// Writing renders: OpenEXR (32-bit float linear sRGB R, G, B plus an XYZ layer XYZ.X/Y/Z),
// PNG (8-bit sRGB with an exposure in stops). Files are written through core/output_file.h: a
// unique temporary name, every write checked, renamed last, so a failed or interrupted write never
// leaves a half file under the final name nor a temporary one beside it.
#include <string>

#include "core/film.h"

namespace kasha {

void writeExr(const Film& film, const std::string& path);
void writePng(const Film& film, const std::string& path, float exposureStops);
// Writes text to path atomically (core/output_file.h).
void writeTextFile(const std::string& path, const std::string& text);

}  // namespace kasha
