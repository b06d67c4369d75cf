#pragma once
// Camera and light subpaths for BDPT (docs/bdpt-mis.md §2).
#include <vector>

#include "core/sampler.h"
#include "scene/scene.h"
#include "core/wavelength_density.h"
#include "integrators/bdpt/path_vertex.h"
#include "integrators/integrator.h"

namespace kasha::bdpt {

// The two exact wavelength families of transport.md §3.
enum class WavelengthMode : uint8_t {
  Shared,       // the light subpath starts at the camera sample's wavelength
  Independent,  // the light subpath draws its own wavelength from the lights' power spectrum
};

struct WalkSettings {
  int maxDepth = 64;  // maximum number of scattering vertices on a full path
  int rrDepth = 3;
  WavelengthMode mode = WavelengthMode::Independent;
  const WavelengthDensity* lightWavelengths = nullptr;  // Independent: the light-start strategy's density
};

// C[0] is the pinhole; C[1] the first hit. lambda is the sensor's wavelength, sensorPdf its
// density (folded into C[1].pdfFwd in Independent mode only, where it does not cancel).
void traceCameraSubpath(const Scene& scene, Vec2 filmPos, float lambda, float sensorPdf, const WalkSettings& ws,
                        Sampler& rng, RayCounter& counter, std::vector<PathVertex>& out);

// L[0] is the light vertex. In Shared mode the subpath starts at `sharedLambda` and stops at its
// first fluorescent event (later vertices could only form paths Shared mode cannot weight).
void traceLightSubpath(const Scene& scene, float sharedLambda, const WalkSettings& ws, Sampler& rng, RayCounter& counter,
                       std::vector<PathVertex>& out);

// Density with which a light subpath starts at light `light` with wavelength lambda: the joint
// p(light, λ) = p(light | λ)·p(λ) in Independent mode, p(light | λ) in Shared mode.
float lightChoicePdf(const Scene& scene, int light, float lambda, const WalkSettings& ws);

}  // namespace kasha::bdpt
