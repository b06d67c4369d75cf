#include "core/spectrum_presets.h"

#include "core/embedded_data.h"
#include "core/spectrum_csv.h"

namespace kasha {
namespace {

Spectrum embeddedColumn(const char* file, const std::string& column) {
  return spectrumFromTable(parseSpectralCsv(embeddedFile(file), file), column).zeroOutside();
}

}  // namespace

std::optional<Spectrum> presetSpectrum(const std::string& name) {
  if (name == "E") return Spectrum::constant(1.0f);
  if (name == "D65") return embeddedColumn("cie_illuminant_D65_1nm.csv", "relative_spd");
  if (name == "A") return embeddedColumn("cie_illuminant_A_1nm.csv", "relative_spd");
  for (int i = 1; i <= 12; ++i)
    if (name == "F" + std::to_string(i)) return embeddedColumn("cie_illuminants_F1-F12_5nm.csv", name);
  return std::nullopt;
}

std::vector<std::string> presetNames() {
  std::vector<std::string> n = {"E", "D65", "A"};
  for (int i = 1; i <= 12; ++i) n.push_back("F" + std::to_string(i));
  return n;
}

}  // namespace kasha
