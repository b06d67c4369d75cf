#pragma once
// Writing renders: OpenEXR (32-bit float linear sRGB R, G, B plus an XYZ layer XYZ.X/Y/Z, and
// optionally spectral bins in the emissive layout of Fichet et al. 2021, core/spectral_exr.h),
// PNG (8-bit sRGB with an exposure in stops). Files are written through core/output_file.h: a
// unique temporary name, every write checked, renamed last, so a failed or interrupted write never
// leaves a half file under the final name nor a temporary one beside it.
#include <string>

#include "core/film.h"
#include "core/spectral_film.h"

namespace kasha {

// With `spectral` (same size as the film), its bins are written as S0.<λ> channels as well.
void writeExr(const Film& film, const std::string& path, const SpectralFilm* spectral = nullptr);
void writePng(const Film& film, const std::string& path, float exposureStops);
// Writes text to path atomically (core/output_file.h).
void writeTextFile(const std::string& path, const std::string& text);

}  // namespace kasha
