#pragma once
// Measured complex indices of refraction η(λ) + i·k(λ) of metals, by chemical symbol ("Au"): the
// tables of scenes/spectra/conductors/ (refractiveindex.info, CC0; each file names its
// measurement), embedded in the binary, 300–830 nm every 5 nm, linear between the rows.
#include <optional>
#include <string>
#include <vector>

#include "core/spectrum.h"

namespace kasha {

struct ComplexIndex {
  Spectrum eta, k;  // relative to the medium outside (air or vacuum)
};

// The metal's index, or nullopt if kasha has no table for it.
std::optional<ComplexIndex> namedConductor(const std::string& symbol);
// The symbols namedConductor knows, in alphabetical order.
std::vector<std::string> conductorNames();

}  // namespace kasha
