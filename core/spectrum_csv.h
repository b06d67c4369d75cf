#pragma once
// Reading tabulated spectra from CSV: `#` comment lines, one header line naming the columns, then
// numeric rows whose first column is the wavelength in nm (strictly increasing).
#include <cstdint>
#include <string>
#include <vector>

#include "core/spectrum.h"

namespace kasha {

struct SpectralTable {
  std::string source;                    // file name (or embedded name) for messages
  std::vector<std::string> columns;      // header names, the wavelength column first
  std::vector<float> lambdas;
  std::vector<std::vector<float>> data;  // data[c][row] for value column c (columns[c + 1])
  std::vector<int> lines;                // file line of each row, for messages
};

// Parses CSV text; `source` names it in errors. Throws InputError on malformed numbers, ragged
// rows, NaN/Inf, or wavelengths that are not strictly increasing.
SpectralTable parseSpectralCsv(const std::string& text, const std::string& source);
// Reads and parses a file; a missing or unreadable file, one that is not a regular file, or one
// larger than kMaxSpectralFileBytes is an InputError naming it.
SpectralTable readSpectralCsv(const std::string& path);
constexpr uint64_t kMaxSpectralFileBytes = uint64_t(256) << 20;

// One column as a spectrum. `column` empty picks the only value column (an error if there are
// several). Negative values are an error naming the line.
Spectrum spectrumFromTable(const SpectralTable& t, const std::string& column);

}  // namespace kasha
