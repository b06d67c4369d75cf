#pragma once
// Integrators by name, for the command line, tests and benchmarks.
#include <memory>
#include <string>
#include <vector>

#include "integrators/integrator.h"

namespace kasha {

// "pt" (path tracing), "lt" (light tracing), "bdpt-shared" / "bdpt-independent" (BDPT in either
// wavelength family; "bdpt" is the independent one), "bdpt-mollified" (independent, with spectral
// mollification of elastic connections), "ppm" (progressive photon mapping). Throws
// std::invalid_argument otherwise.
// settings.heroWavelengths = kAutoLanes becomes defaultLanes(name, settings) (BDPT: its own).
// Throws FluorescentLanesError for settings.fluorescentLanes = End with any but pt and lt.
std::unique_ptr<Integrator> makeIntegrator(const std::string& name, const Scene& scene, const RenderSettings& settings);
std::vector<std::string> integratorNames();

// Wavelength lanes of an integrator when the settings leave them to it: kDefaultLanes for lt, and
// for pt when its sensor strategy is one density and next-event estimation shares the event's
// excitation wavelength (what lanes need); 1 otherwise (ppm: no lanes yet). The BDPT estimators
// decide for themselves (they need the scene): Bdpt's constructor.
int defaultLanes(const std::string& name, const RenderSettings& settings);

}  // namespace kasha
