#pragma once
// Scene-file parsing of the measured fluorescent materials (called from material_json.cpp):
//   {"type": "zhdanov", "gloss": ρ_g, "gloss_exponent": n, "passive": <spectrum>,
//    "excitation": <spectrum>, "emission": <spectrum>}                       (zhdanov_bdf.h)
//   {"type": "measured_reradiation", "file": "m.csv" | "m.exr", "noise_floor": 0.002}
//                                                                              (measured_reradiation.h)
// Both take the optional "allow_unphysical" read by the caller.
#include <memory>

#include "core/json_fields.h"
#include "core/spectrum_json.h"
#include "materials/material.h"

namespace kasha {

std::unique_ptr<Material> parseZhdanov(JsonFields& f, const SpectrumContext& ctx, WavelengthRange range,
                                       bool allowUnphysical);
std::unique_ptr<Material> parseMeasuredReradiation(JsonFields& f, const SpectrumContext& ctx, WavelengthRange range,
                                                   bool allowUnphysical);

}  // namespace kasha
