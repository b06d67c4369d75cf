#pragma once
// Integrators by name, for the command line, tests and benchmarks.
#include <memory>
#include <string>
#include <vector>

#include "integrators/integrator.h"

namespace kasha {

// "pt" (path tracing), "lt" (light tracing), "bdpt" (bidirectional path tracing: both wavelength
// families in one MIS, a pilot choosing per scene whether to run one alone; render/bdpt), "ppm"
// (progressive photon mapping; render/ppm), and the configurations of the bidirectional engine
// with vertex merging (render/vcm): "vcm" (vertex connection and merging), "vc" / "bpm" (its
// connections alone / its merges alone). The list is integratorNames() (docs/integrators.md); the
// names of integratorAliases() stand for one of them with settings.
// Throws std::invalid_argument otherwise.
// settings.heroWavelengths = kAutoLanes becomes defaultLanes(name, settings) (BDPT: its own).
// Throws FluorescentLanesError for settings.fluorescentLanes = End with any but pt and lt.
std::unique_ptr<Integrator> makeIntegrator(const std::string& name, const Scene& scene, const RenderSettings& settings);
std::vector<std::string> integratorNames();
// Empty if `name` is an integrator or an alias, else why not: "unknown integrator 'x' (pt, lt, ...)".
std::string integratorNameError(const std::string& name);

// Names of earlier versions that stand for an integrator with settings: "bdpt-shared",
// "bdpt-independent" (bdpt with one wavelength family) and "bdpt-mollified" (the own family with
// spectral mollification).
struct IntegratorAlias {
  std::string name, integrator;
  std::vector<std::string> settings;  // as `--set` takes them: "bdpt.families=shared"
  void (*apply)(RenderSettings&);     // the same settings, written into a RenderSettings
};
const std::vector<IntegratorAlias>& integratorAliases();
// The integrator `name` stands for, with an alias's settings written into `settings` (the alias
// wins over the scene's); any other name as it is.
std::string resolveIntegrator(const std::string& name, RenderSettings& settings);

// Why the integrator `name` does not read the render object's setting `key` (a path such as
// "ppm.direct", docs/scene-format.md), or an empty string if it reads it. The settings only some
// integrators read are listed here; a render that sets one for another integrator is refused
// (render_job.h) rather than silently ignored.
std::string settingNotRead(const std::string& name, const std::string& key);

// Wavelength lanes of an integrator when the settings leave them to it: kDefaultLanes for lt, and
// for pt and ppm when the sensor strategy is one density and next-event estimation shares the
// event's excitation wavelength (what their camera lanes need); 1 otherwise. The bidirectional
// engine's configurations are not asked: their constructors take kDefaultLanes themselves.
int defaultLanes(const std::string& name, const RenderSettings& settings);

}  // namespace kasha
