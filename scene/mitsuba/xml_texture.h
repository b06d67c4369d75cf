#pragma once
// Mitsuba's <texture type="bitmap"> as a kasha reflectance texture (docs/scene-format.md
// "Textures"; docs/mitsuba-import.md): filename → "file" (relative to the XML file), filter_type
// bilinear | nearest → "filter", wrap_mode repeat | mirror | clamp → "wrap", and the image's RGB
// as a colour ("channel": "rgb", Jakob–Hanika spectra like <rgb>). Mitsuba decodes 8-bit images
// from sRGB unless raw = true; kasha reads PNG values as linear data, so a PNG without raw = true
// is noted as an approximation (OpenEXR is linear in both). Anything else is an error.
#include <nlohmann/json.hpp>

#include "scene/mitsuba/xml_plugin.h"

namespace kasha::mitsuba {

// The kasha texture field of the <texture> element `node`.
nlohmann::json bitmapTexture(XmlImport& xml, pugi::xml_node node);

}  // namespace kasha::mitsuba
