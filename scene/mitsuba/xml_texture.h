#pragma once
// Mitsuba's <texture> elements as kasha texture fields (docs/scene-format.md "Textures";
// docs/mitsuba-import.md), nested in a property or declared at the top level with an id and
// referred to by <ref name="..." id="..."/> (translated where they are used):
// - bitmap (reflectances only): filename → "file" (relative to the XML file), filter_type
//   bilinear | nearest → "filter", wrap_mode repeat | mirror | clamp → "wrap", and the image's
//   RGB as a colour ("channel": "rgb", Jakob–Hanika spectra like <rgb>). Mitsuba decodes 8-bit
//   images from sRGB unless raw = true; kasha reads PNG values as linear data, so a PNG without
//   raw = true is noted as an approximation (OpenEXR is linear in both).
// - checkerboard: color0, color1 (<float>, <rgb>, or a constant <spectrum>; defaults 0.4, 0.2)
//   and to_uv (a <transform>, of which the 2D affine part is used, as Mitsuba extracts it).
// - mesh_attribute: name (vertex_… or face_…; PLY meshes).
// Anything else is an error.
#include <nlohmann/json.hpp>

#include "scene/mitsuba/xml_plugin.h"

namespace kasha::mitsuba {

// How a property reads a texture: as a reflectance (colours allowed) or as a scalar (Mitsuba's
// eval_1: roughness).
enum class TextureUse { Reflectance, Scalar };

// Whether the property element `p` is a texture (<texture> or <ref> to a top-level one).
bool isTexture(pugi::xml_node p);
// The kasha texture field of the texture property `p` (a <texture>, or a <ref> to a <texture id>
// declared before it).
nlohmann::json textureField(XmlImport& xml, pugi::xml_node p, TextureUse use);

}  // namespace kasha::mitsuba
