#pragma once
// Media in scene files (docs/scene-format.md "Media"; core/medium.h):
//   {"type": "homogeneous", "sigma_a": <spectrum>, "sigma_s": <spectrum>, "g": g,
//    "fluorophores": [{"sigma_f": <spectrum>, "emission": <spectrum>, "yield": Y}, ...]}
// σ_a, σ_s and σ_f are per unit of scene length (absent: 0; g absent: 0, isotropic). A
// fluorophore may give its absorption as a solution's instead of σ_f: "molar_absorption" ε(λ) in
// L·mol⁻¹·cm⁻¹ (decadic, as spectroscopists tabulate it) and "concentration" c in mol/L, with the
// medium's "length_unit" naming the scene's unit ("m", "cm", "mm" or "um"): then
// σ_f(λ) = ln 10 · ε(λ) · c · (centimetres per scene unit).
#include <memory>
#include <string>

#include <nlohmann/json.hpp>

#include "core/medium.h"
#include "core/spectrum_json.h"

namespace kasha {

// Throws InputError naming the field.
std::unique_ptr<Medium> parseMedium(const std::string& name, const nlohmann::json& v, const SpectrumContext& ctx,
                                    const std::string& pointer, WavelengthRange range);

}  // namespace kasha
