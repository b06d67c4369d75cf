#pragma once
// Texture fields of materials in scene files (docs/scene-format.md, "Textures"):
//   "<parameter>_texture": "image.png" | {"file": "image.exr", "channel": "mean" | "r" | "g" | "b" | "a",
//                                        "wrap": "repeat" | "clamp" | "mirror", "filter": "bilinear" | "nearest"}
//                        | {"type": "checkerboard", "color0": 0.4, "color1": 0.2, "to_uv": [[a, b, c], [d, e, f]]}
//                        | {"type": "mesh_attribute", "name": "vertex_color" | "face_color" | ...}
// A reflectance's texture also takes "channel": "rgb" (a linear sRGB colour, materials/surface_texture.h)
// and checkerboard colours [r, g, b]; a mesh attribute is read as a colour there, as one channel
// elsewhere (the scene loader checks the meshes).
// Images load through the scene's TextureLoader (memory limit before decoding); a bad file, value
// or option is an InputError naming the field.
#include "core/json_fields.h"
#include "core/spectrum_json.h"
#include "materials/surface_texture.h"

namespace kasha {

// The texture of a scalar parameter; none when the field is absent.
ScalarTexture parseScalarTexture(JsonFields& f, const std::string& key, const SpectrumContext& ctx);
// The texture of a reflectance spectrum (one channel or "rgb"); none when the field is absent.
ReflectanceTexture parseReflectanceTexture(JsonFields& f, const std::string& key, const SpectrumContext& ctx);
// The texture of a GGX roughness: one texture (a factor on both axes) or [α_x's, α_y's], where
// null leaves an axis untextured.
AlphaTexture parseAlphaTexture(JsonFields& f, const std::string& key, const SpectrumContext& ctx);

}  // namespace kasha
