#pragma once
// Mitsuba BSDFs as kasha materials (docs/mitsuba-import.md has the table): diffuse → lambertian;
// conductor / roughconductor → mirror / rough_conductor with the normal-incidence reflectance of
// the given η, k; dielectric / roughdielectric → dielectric / rough_dielectric; plastic /
// roughplastic → coated_fluorescent without fluorescence; twosided → its nested BSDF (kasha's
// opaque materials reflect on both sides); mask → mask; blendbsdf → blend. kasha's own materials (jung_fluorescent, zhdanov,
// coated_fluorescent, measured_reradiation) are an extension whose properties are the JSON
// fields of docs/scene-format.md. Approximations are recorded as notes.
#include <nlohmann/json.hpp>

#include "scene/mitsuba/xml_plugin.h"

namespace kasha::mitsuba {

// The kasha material JSON of a <bsdf> element.
nlohmann::json bsdfMaterial(XmlImport& xml, pugi::xml_node bsdf);
// Whether `bsdf` is Mitsuba's `null` BSDF (light passes through unchanged), which kasha writes as a
// shape without a material: an index-matched medium boundary. Reads (and checks) the element.
bool isNullBsdf(XmlImport& xml, pugi::xml_node bsdf);

}  // namespace kasha::mitsuba
