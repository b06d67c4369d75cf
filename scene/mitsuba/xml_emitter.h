#pragma once
// Mitsuba emitters that are not attached to a shape, as kasha lights: point → point, spot → spot
// (Mitsuba's linear falloff between beam_width and cutoff_angle becomes kasha's smooth one),
// directional → distant, constant → environment, envmap → envmap (kasha's importance-sampled
// equirectangular light, core/envmap_light.h).
#include "scene/mitsuba/scene_json.h"

namespace kasha::mitsuba {

// Appends the kasha light of a top-level <emitter> element to `out`.
void addEmitter(XmlImport& xml, pugi::xml_node emitter, SceneJson& out);

}  // namespace kasha::mitsuba
