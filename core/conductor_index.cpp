#include "core/conductor_index.h"

#include <algorithm>

#include "core/embedded_data.h"
#include "core/spectrum_csv.h"

namespace kasha {

std::vector<std::string> conductorNames() {
  return {"Ag", "Al", "Au", "Be", "Co", "Cr", "Cu", "Fe", "Mo", "Nb", "Ni", "Pd", "Pt", "Rh", "Ti", "V", "W"};
}

std::optional<ComplexIndex> namedConductor(const std::string& symbol) {
  const std::vector<std::string> names = conductorNames();
  if (std::find(names.begin(), names.end(), symbol) == names.end()) return std::nullopt;
  const std::string file = symbol + ".csv";
  const SpectralTable t = parseSpectralCsv(embeddedFile(file), file);
  return ComplexIndex{spectrumFromTable(t, "eta"), spectrumFromTable(t, "k")};
}

}  // namespace kasha
