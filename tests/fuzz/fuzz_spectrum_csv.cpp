// libFuzzer target: the spectrum and matrix reader (core/spectrum_csv.h) on arbitrary text. A
// table is either rejected with an InputError or satisfies what the reader promises: a header,
// strictly increasing positive finite wavelengths, rectangular finite data; each column is then a
// spectrum that is rejected (negative values) or evaluates and integrates to finite non-negative
// numbers. A matrix file (`kasha matrix` output) is the same table with one column per output
// wavelength. Anything else is a finding.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "core/error.h"
#include "core/spectrum_csv.h"

namespace {

void require(bool ok, const char* what) {
  if (!ok) {
    std::fprintf(stderr, "fuzz_spectrum_csv: broken promise: %s\n", what);
    std::abort();
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace kasha;
  SpectralTable t;
  try {
    t = parseSpectralCsv(std::string(reinterpret_cast<const char*>(data), size), "fuzz.csv");
  } catch (const InputError&) {
    return 0;
  }
  require(t.columns.size() >= 2, "a wavelength column and a value column");
  require(!t.lambdas.empty(), "at least one row");
  require(t.data.size() + 1 == t.columns.size(), "one data vector per value column");
  require(t.lines.size() == t.lambdas.size(), "a line number per row");
  for (size_t i = 0; i < t.lambdas.size(); ++i) {
    require(std::isfinite(t.lambdas[i]) && t.lambdas[i] > 0.0f, "finite positive wavelengths");
    require(i == 0 || t.lambdas[i] > t.lambdas[i - 1], "strictly increasing wavelengths");
    require(i == 0 || t.lines[i] > t.lines[i - 1], "increasing line numbers");
  }
  for (const auto& column : t.data) {
    require(column.size() == t.lambdas.size(), "rectangular data");
    for (float v : column) require(std::isfinite(v), "finite values");
  }
  for (size_t c = 1; c < t.columns.size(); ++c) {
    Spectrum s;
    try {
      s = spectrumFromTable(t, t.columns[c]);
    } catch (const InputError&) {
      continue;  // a negative value, or a duplicated column name
    }
    const float lo = t.lambdas.front(), hi = t.lambdas.back();
    for (float l : {lo, hi, 0.5f * (lo + hi), lo - 1.0f, hi + 1.0f, 360.0f, 555.0f, 830.0f}) {
      const float v = s(l);
      require(std::isfinite(v) && v >= 0.0f, "finite non-negative values");
    }
    require(s.maxValue(360.0f, 830.0f) >= 0.0f && s.minValue(360.0f, 830.0f) >= 0.0f, "value bounds");
    const float integral = s.integral(360.0f, 830.0f);
    require(!std::isnan(integral) && integral >= 0.0f, "a non-negative integral (possibly infinite)");
    (void)s.zeroOutside().integral(lo, hi);
  }
  return 0;
}
