#pragma once
// Named spectra built from the embedded CIE tables: illuminants D65, A, F1–F12 (relative SPD as
// tabulated by the CIE, 100 at 560 nm for D65 and A) and E (equal energy, 1 everywhere).
#include <optional>
#include <string>
#include <vector>

#include "core/spectrum.h"

namespace kasha {

std::optional<Spectrum> presetSpectrum(const std::string& name);
std::vector<std::string> presetNames();

}  // namespace kasha
