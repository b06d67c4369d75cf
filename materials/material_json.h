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
//   {"type": "rough_conductor", "reflectance": <spectrum F0>, "alpha": α | [α_x, α_y]}
//   {"type": "rough_dielectric", "ior": <index>, "alpha": α | [α_x, α_y]}
//   {"type": "coated_fluorescent", <the jung_fluorescent fields>, "coat_ior": <index>,
//    "coat_alpha": α | [α_x, α_y]} (docs/layered.md)
//   {"type": "normal_map", "normals": <texture>, "material": <material>} and {"type": "bump_map",
//    "height": <texture>, "scale": s, "material": <material>}: the material in a shading frame
//    tilted by a tangent-space normal map or a height map's gradient (normal_perturbation.h)
//   {"type": "mask", "opacity": α, "opacity_texture": <texture>, "material": <untextured material>}:
//    light passes straight on with probability 1 − α (opacity_mask.h)
//   {"type": "blend", "weight": w, "weight_texture": <texture>, "materials": [<untextured material>,
//    <untextured material>]}: (1 − w)·the first + w·the second (blend.h)
// Every parameter named above except the indices of refraction may be textured by a
// "<parameter>_texture" field (texture_json.h, docs/scene-format.md "Textures").
#include <memory>

#include <nlohmann/json.hpp>

#include "core/spectrum_json.h"
#include "materials/material.h"

namespace kasha {

std::unique_ptr<Material> parseMaterial(const nlohmann::json& v, const SpectrumContext& ctx, const std::string& pointer,
                                        WavelengthRange range);

}  // namespace kasha
