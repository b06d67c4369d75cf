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
std::unique_ptr<Integrator> makeIntegrator(const std::string& name, const Scene& scene, const RenderSettings& settings);
std::vector<std::string> integratorNames();

}  // namespace kasha
