#pragma once
// Mitsuba's <sensor> of type perspective, thinlens or orthographic (fov, fov_axis, focal_length,
// aperture_radius, focus_distance, to_world, its <film> size and <sampler> sample count) as kasha's camera and samples per pixel, and <integrator type="path">'s
// max_depth and rr_depth as kasha's render settings.
#include "scene/mitsuba/scene_json.h"

namespace kasha::mitsuba {

void addSensor(XmlImport& xml, pugi::xml_node sensor, SceneJson& out);
void addIntegrator(XmlImport& xml, pugi::xml_node integrator, SceneJson& out);

// kasha's vertical field of view (degrees) of Mitsuba's `fov` measured along `axis` (x, y,
// diagonal, smaller, larger) on a width × height film; empty for an unknown axis.
std::optional<float> verticalFov(float fov, const std::string& axis, int width, int height);

}  // namespace kasha::mitsuba
