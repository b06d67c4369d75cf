#include "core/spectrum_csv.h"

#include <cmath>
#include <cstdlib>
#include <sstream>

#include "core/error.h"
#include "core/input_file.h"

namespace kasha {
namespace {

std::vector<std::string> splitCsv(const std::string& line) {
  std::vector<std::string> out;
  std::string cell;
  std::istringstream ss(line);
  while (std::getline(ss, cell, ',')) {
    const auto b = cell.find_first_not_of(" \t\r");
    const auto e = cell.find_last_not_of(" \t\r");
    out.push_back(b == std::string::npos ? "" : cell.substr(b, e - b + 1));
  }
  if (!line.empty() && line.back() == ',') out.push_back("");
  return out;
}

}  // namespace

SpectralTable parseSpectralCsv(const std::string& text, const std::string& source) {
  SpectralTable t;
  t.source = source;
  // A UTF-8 byte order mark (spreadsheet exports) is not part of the first line's text.
  const bool bom = text.compare(0, 3, "\xEF\xBB\xBF") == 0;
  std::istringstream in(bom ? text.substr(3) : text);
  std::string line;
  int lineNo = 0;
  bool haveHeader = false;
  while (std::getline(in, line)) {
    ++lineNo;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    const auto first = line.find_first_not_of(" \t");
    if (first == std::string::npos || line[first] == '#') continue;
    const std::vector<std::string> cells = splitCsv(line);
    const std::string where = source + ":" + std::to_string(lineNo);
    if (!haveHeader) {
      if (cells.size() < 2) throw InputError(where, "header", "needs a wavelength column and at least one value column");
      char* end = nullptr;
      std::strtod(cells[0].c_str(), &end);
      if (!cells[0].empty() && end == cells[0].c_str() + cells[0].size())  // a number where the wavelength column's name belongs
        throw InputError(where, "header", "the header line is missing (found numbers, expected column names)");
      t.columns = cells;
      t.data.assign(cells.size() - 1, {});
      haveHeader = true;
      continue;
    }
    if (cells.size() != t.columns.size())
      throw InputError(where, "", "row has " + std::to_string(cells.size()) + " fields, header has " +
                                      std::to_string(t.columns.size()));
    std::vector<float> row;
    for (size_t c = 0; c < cells.size(); ++c) {
      // strtod, not stod: an overflow is a non-finite value, not an exception.
      char* end = nullptr;
      const double v = std::strtod(cells[c].c_str(), &end);
      if (cells[c].empty() || end != cells[c].c_str() + cells[c].size())  // a NUL inside ends c_str() early
        throw InputError(where, t.columns[c], "'" + cells[c] + "' is not a number");  // a NUL shown as \x00 (error.h)
      if (!std::isfinite(v)) throw InputError(where, t.columns[c], "value is not finite");
      if (!std::isfinite(float(v)))
        throw InputError(where, t.columns[c], "value " + cells[c] + " is out of range of a 32-bit float");
      row.push_back(float(v));
    }
    if (!t.lambdas.empty() && row[0] <= t.lambdas.back())
      throw InputError(where, t.columns[0], "wavelengths must be strictly increasing (" + cells[0] +
                                                " after " + std::to_string(t.lambdas.back()) + ")");
    if (row[0] <= 0.0f) throw InputError(where, t.columns[0], "wavelength must be positive");
    t.lambdas.push_back(row[0]);
    for (size_t c = 1; c < row.size(); ++c) t.data[c - 1].push_back(row[c]);
    t.lines.push_back(lineNo);
  }
  if (!haveHeader) throw InputError(source, "", "no header line");
  if (t.lambdas.empty()) throw InputError(source, "", "no data rows");
  return t;
}

SpectralTable readSpectralCsv(const std::string& path) {
  return parseSpectralCsv(readInputFile(path, "spectrum file", kMaxSpectralFileBytes), path);
}

Spectrum spectrumFromTable(const SpectralTable& t, const std::string& column) {
  size_t c = 0;
  if (column.empty()) {
    if (t.data.size() != 1)
      throw InputError(t.source, "column", "the file has " + std::to_string(t.data.size()) +
                                               " value columns; name one");
  } else {
    size_t i = 1;
    while (i < t.columns.size() && t.columns[i] != column) ++i;
    if (i == t.columns.size()) throw InputError(t.source, "column", "no column named '" + column + "'");
    c = i - 1;
  }
  const std::vector<float>& v = t.data[c];
  for (size_t r = 0; r < v.size(); ++r)
    if (v[r] < 0.0f)
      throw InputError(t.source + ":" + std::to_string(t.lines[r]), t.columns[c + 1], "negative value " + std::to_string(v[r]));
  return Spectrum::piecewiseLinear(t.lambdas, v);
}

}  // namespace kasha
