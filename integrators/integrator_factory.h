#pragma once
// Integrators by name, for the command line, tests and benchmarks.
#include <memory>
#include <string>
#include <vector>

#include "integrators/integrator.h"

namespace kasha {

// "pt" (path tracing), "lt" (light tracing), "bdpt" (BDPT with both wavelength families in one MIS,
// a pilot choosing per scene whether to run one alone), "bdpt-shared" / "bdpt-independent" (BDPT in
// one wavelength family), "bdpt-mollified" (independent, with spectral mollification of elastic
// connections), "ppm" (progressive photon mapping), "vcm" (vertex connection and merging), "vc" /
// "bpm" (its connections alone / its merges alone); the list is integratorNames() (docs/integrators.md).
// Throws std::invalid_argument otherwise.
// settings.heroWavelengths = kAutoLanes becomes defaultLanes(name, settings) (BDPT: its own).
// Throws FluorescentLanesError for settings.fluorescentLanes = End with any but pt and lt.
std::unique_ptr<Integrator> makeIntegrator(const std::string& name, const Scene& scene, const RenderSettings& settings);
std::vector<std::string> integratorNames();

// Why the integrator `name` does not read the render object's setting `key` (a path such as
// "ppm.direct", docs/scene-format.md), or an empty string if it reads it. The settings only some
// integrators read are listed here; a render that sets one for another integrator is refused
// (render_job.h) rather than silently ignored.
std::string settingNotRead(const std::string& name, const std::string& key);

// Wavelength lanes of an integrator when the settings leave them to it: kDefaultLanes for lt, and
// for pt and ppm when the sensor strategy is one density and next-event estimation shares the
// event's excitation wavelength (what their camera lanes need); 1 otherwise. The BDPT estimators and
// vcm, vc, bpm are not asked: their constructors take kDefaultLanes themselves.
int defaultLanes(const std::string& name, const RenderSettings& settings);

}  // namespace kasha
