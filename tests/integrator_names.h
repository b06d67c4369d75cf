#pragma once
// Integrators by the names the tests run: the CLI's, and "bdpt.both", the unified bdpt with both
// light-subpath families fixed (RenderSettings::bdptFamilies). "bdpt" chooses its families with a
// pilot (docs/bdpt-mis.md §13); "bdpt.both" keeps the estimator that pilot may set aside under the
// same tests.
#include <memory>
#include <string>

#include "integrators/integrator_factory.h"

namespace kasha::test {

inline std::unique_ptr<Integrator> makeTestIntegrator(const std::string& name, const Scene& scene,
                                                      RenderSettings settings) {
  if (name != "bdpt.both") return makeIntegrator(name, scene, settings);
  settings.bdptFamilies = BdptFamilies::Both;
  return makeIntegrator("bdpt", scene, settings);
}

}  // namespace kasha::test
