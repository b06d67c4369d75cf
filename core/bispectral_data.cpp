#include "core/bispectral_data.h"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iomanip>
#include <sstream>

#include "core/error.h"
#include "core/spectrum_csv.h"

namespace kasha {

BispectralData readBispectralCsv(const std::string& path) {
  const SpectralTable t = readSpectralCsv(path);  // ragged rows, bad numbers, wavelength order
  BispectralData d;
  d.source = path;
  d.out = t.lambdas;
  for (size_t c = 1; c < t.columns.size(); ++c) {
    const std::string& name = t.columns[c];
    const char* s = name.c_str() + 3;
    char* end = nullptr;
    errno = 0;
    const float l = name.rfind("ex_", 0) == 0 ? std::strtof(s, &end) : NAN;
    if (!(end && *end == '\0' && end != s && errno == 0 && std::isfinite(l) && l > 0.0f))
      throw InputError(path, name, "header cell must be ex_<input wavelength in nm>, e.g. ex_450");
    if (!d.in.empty() && l <= d.in.back())
      throw InputError(path, name, "input wavelengths must be strictly increasing (" + t.columns[c - 1] + " comes first)");
    d.in.push_back(l);
  }
  d.value.assign(d.in.size() * d.out.size(), 0.0f);
  for (size_t i = 0; i < d.in.size(); ++i)
    for (size_t o = 0; o < d.out.size(); ++o) d.at(o, i) = t.data[i][o];
  return d;
}

void writeBispectralCsv(const std::string& path, const BispectralData& d, const std::string& comment) {
  std::ofstream f(path);
  if (!f) throw InputError(path, "", "cannot open for writing");
  f << "# " << comment << "\n# Rows: output wavelength (nm). Columns ex_<nm>: input wavelength.\n";
  f << "wavelength_out_nm";
  for (const float l : d.in) f << ",ex_" << l;
  f << "\n" << std::setprecision(9);
  for (size_t o = 0; o < d.out.size(); ++o) {
    f << d.out[o];
    for (size_t i = 0; i < d.in.size(); ++i) f << "," << d.at(o, i);
    f << "\n";
  }
  if (!f) throw InputError(path, "", "write failed");
}

std::vector<float> bandWidths(const std::vector<float>& g) {
  std::vector<float> w(g.size(), 1.0f);
  for (size_t k = 0; k < g.size() && g.size() > 1; ++k)
    w[k] = k == 0 ? g[1] - g[0] : k + 1 == g.size() ? g[k] - g[k - 1] : 0.5f * (g[k + 1] - g[k - 1]);
  return w;
}

std::string formatNm(float lambda) {
  std::ostringstream s;
  s << lambda;
  return s.str();
}

}  // namespace kasha
