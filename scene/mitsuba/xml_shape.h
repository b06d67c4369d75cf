#pragma once
// Mitsuba shapes as kasha shapes: obj / ply / serialized → mesh with a transform; rectangle →
// rectangle by its transformed corners; cube → six rectangles; sphere → sphere (uniform scale
// only); cylinder → cylinder (p0, p1, radius and to_world as its transform); disk → kasha's
// tessellated disk. A nested <bsdf> or <ref> sets the material (default: Mitsuba's diffuse 0.5),
// a nested <emitter type="area"> the emission.
#include "scene/mitsuba/scene_json.h"

namespace kasha::mitsuba {

// Appends the kasha shape(s) of a <shape> element (and its nested material) to `out`.
void addShape(XmlImport& xml, pugi::xml_node shape, SceneJson& out);

}  // namespace kasha::mitsuba
