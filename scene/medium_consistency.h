#pragma once
// A check of a scene's medium assignments (docs/media.md §1): rays from the camera cross every
// surface (as if all were index-matched), keeping track of the medium as the shapes'
// MediumInterfaces say, and each crossing of a shape that names its media must come from the side
// whose medium the ray is in. Where two media overlap, a shape's exterior is not the medium around
// it, or the camera's medium is not the one it sits in, some such ray meets a shape from the wrong
// medium. A sample of rays cannot prove a scene consistent; every disagreement it finds is real
// (or a surface that coincides with another, whose crossing order, and so the medium, is then left
// to rounding).
#include <string>

#include "scene/scene.h"

namespace kasha {

// Throws InputError(file, "/shapes/<i>" or "/camera/medium", reason) naming the shapes involved.
void checkMediumAssignments(const Scene& scene, const std::string& file);

}  // namespace kasha
