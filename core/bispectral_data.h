#pragma once
// A measured bispectral reflectance (reradiation) matrix, as a fluorimeter or a bispectral camera
// gives it: value(λ_o; λ_i) is the reflectance factor of the output band around λ_o for light
// arriving at λ_i (dimensionless, per output band). Where λ_o = λ_i it is the ordinary
// (elastic) reflectance; elsewhere reradiation.
//
// Files:
// - CSV (the layout of ../shared/data/spectra/bispectral_*.csv): `#` comments, a header
//   "<anything>,ex_<λ_i>,ex_<λ_i>,...", then one row per output wavelength: λ_o, values.
// - OpenEXR in the bispectral layout of Fichet, Pacanowski & Wilkie (2021, JCGT 10(3), "An OpenEXR
//   layout for spectral images"): channel "T.<λ>nm" holds the diagonal (reflective) value at λ,
//   "T.<λ_i>nm.<λ_o>nm" the reradiation from λ_i to λ_o; numbers use a decimal comma
//   ("T.550,000000nm") and may carry an SI prefix on m or Hz. See bispectral_exr.h.
#include <string>
#include <vector>

namespace kasha {

struct BispectralData {
  std::string source;       // file name, for messages
  std::vector<float> in;    // λ_i, strictly increasing
  std::vector<float> out;   // λ_o, strictly increasing
  std::vector<float> value; // value[o * in.size() + i]

  float at(size_t o, size_t i) const { return value[o * in.size() + i]; }
  float& at(size_t o, size_t i) { return value[o * in.size() + i]; }
};

// Reads the CSV layout above. Throws InputError naming the file, the column or line and the reason
// (missing file, ragged rows, a header cell that is not ex_<number>, non-increasing wavelengths).
BispectralData readBispectralCsv(const std::string& path);
// Writes the same layout (with a comment naming `comment`).
void writeBispectralCsv(const std::string& path, const BispectralData& d, const std::string& comment);

// Width of each band of a wavelength grid: from the midpoint with the previous knot to the
// midpoint with the next one, the end bands as wide as their one neighbour spacing (1 for a
// single knot). Turns per-band values into densities per nm.
std::vector<float> bandWidths(const std::vector<float>& grid);
// A wavelength for messages: "450", "452.5".
std::string formatNm(float lambda);

}  // namespace kasha
