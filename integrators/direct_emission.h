#pragma once
// An area emitter seen directly by the camera ray contributes ∫ W(λ)·L_e(λ) dλ to the film, which
// is known in closed form (Observer::xyz). Integrators that estimate the sensor's wavelength
// integral with lanes add it exactly where no weight depends on the wavelength
// (docs/wavelength-sampling.md "Hero wavelengths").
#include <vector>

#include "core/math.h"
#include "scene/scene.h"

namespace kasha {

// Per light: the XYZ of its emission seen from its emitting side; zero for lights not on a shape.
std::vector<Vec3> directEmissionXyz(const Scene& scene);

}  // namespace kasha
