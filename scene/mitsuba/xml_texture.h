#pragma once
// Mitsuba's <texture type="bitmap"> as a kasha reflectance texture (docs/scene-format.md
// "Textures"; docs/mitsuba-import.md): filename → "file" (relative to the XML file), filter_type
// bilinear | nearest → "filter", wrap_mode repeat | mirror | clamp → "wrap", and the image's RGB
// as a colour ("channel": "rgb", Jakob–Hanika spectra like <rgb>). Mitsuba decodes integer-coded
// images (PNG, JPEG, BMP, TGA) from sRGB unless raw = true: without raw the texture's "encoding"
// is "srgb" (OpenEXR and HDR are linear either way). Anything else is an error.
#include <nlohmann/json.hpp>

#include "scene/mitsuba/xml_plugin.h"

namespace kasha::mitsuba {

// The kasha texture field of the <texture> element `node`.
nlohmann::json bitmapTexture(XmlImport& xml, pugi::xml_node node);

}  // namespace kasha::mitsuba
