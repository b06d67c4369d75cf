#pragma once
// Materials in scene files:
//   {"type": "lambertian", "reflectance": <spectrum>}
//   {"type": "jung_fluorescent", "absorption": <spectrum>, "emission": <spectrum>,
//    "reflectance": <spectrum>, "c": 0..1, "Q": 0..1}
#include <memory>

#include <nlohmann/json.hpp>

#include "core/spectrum_json.h"
#include "materials/material.h"

namespace kasha {

std::unique_ptr<Material> parseMaterial(const nlohmann::json& v, const SpectrumContext& ctx, const std::string& pointer,
                                        WavelengthRange range);

}  // namespace kasha
