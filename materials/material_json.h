#pragma once
// Materials in scene files:
//   {"type": "lambertian", "reflectance": <spectrum>}
//   {"type": "jung_fluorescent", "absorption": <spectrum>, "emission": <spectrum>,
//    "reflectance": <spectrum>, "c": 0..1, "Q": 0..1}
//   {"type": "mirror", "reflectance": <spectrum>}
//   {"type": "dielectric", "ior": <index of refraction>}, the index being a number ≥ 1, a preset
//    ("BK7", "fused_silica"), {"type": "cauchy", "A": a, "B": b, "C": c} (λ in µm, C optional)
//    or {"type": "sellmeier", "B": [3 numbers], "C": [3 numbers in µm²]} (ior.h)
//   {"type": "zhdanov", ...}, {"type": "measured_reradiation", ...}  (measured_material_json.h)
//   {"type": "file", "file": "m.json"}: a material object in its own file (paths relative to it)
#include <memory>

#include <nlohmann/json.hpp>

#include "core/spectrum_json.h"
#include "materials/material.h"

namespace kasha {

std::unique_ptr<Material> parseMaterial(const nlohmann::json& v, const SpectrumContext& ctx, const std::string& pointer,
                                        WavelengthRange range);

}  // namespace kasha
