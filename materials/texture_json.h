#pragma once
// Texture fields of materials in scene files (docs/scene-format.md, "Textures"):
//   "<parameter>_texture": "image.png" | {"file": "image.exr", "channel": "mean" | "r" | "g" | "b" | "a",
//                                        "wrap": "repeat" | "clamp" | "mirror", "filter": "bilinear" | "nearest",
//                                        "encoding": "linear" | "srgb"}
// A reflectance's texture also takes "channel": "rgb" (a linear sRGB colour, materials/surface_texture.h).
// Images load through the scene's TextureLoader (memory limit before decoding); a bad file, value
// or option is an InputError naming the field.
#include "core/json_fields.h"
#include "core/spectrum_json.h"
#include "materials/surface_texture.h"

namespace kasha {

// The texture of a scalar parameter; no image when the field is absent.
ScalarTexture parseScalarTexture(JsonFields& f, const std::string& key, const SpectrumContext& ctx);
// The texture of a reflectance spectrum (one channel or "rgb"); no image when the field is absent.
ReflectanceTexture parseReflectanceTexture(JsonFields& f, const std::string& key, const SpectrumContext& ctx);
// The image of a field that must be present: one channel, or (normals) the three of a normal map
// ("channel" rgb, its default there).
std::shared_ptr<const ImageTexture> parseRequiredTexture(JsonFields& f, const std::string& key, const SpectrumContext& ctx,
                                                         bool normals);

}  // namespace kasha
