#pragma once
// Integrators by the names the tests run: the CLI's, "bdpt.both", the unified bdpt with both
// light-subpath families fixed (render/bdpt/families), and "vcm.bidirectional" and
// "vcm.gather", vcm with its light subpaths (and its gather) fixed (render/vcm/paths). "bdpt" chooses its families and "vcm" its
// subpaths with a pilot (docs/bdpt-mis.md §13, §14); these keep the estimators the pilots may set
// aside under the same tests.
#include <memory>
#include <string>

#include "integrators/integrator_factory.h"

namespace kasha::test {

inline std::unique_ptr<Integrator> makeTestIntegrator(const std::string& name, const Scene& scene,
                                                      RenderSettings settings) {
  if (name == "bdpt.both") {
    settings.bdpt.families = BdptFamilies::Both;
    return makeIntegrator("bdpt", scene, settings);
  }
  if (name == "vcm.bidirectional" || name == "vcm.gather") {
    settings.vcm.paths = name == "vcm.gather" ? VcmPaths::Gather : VcmPaths::Bidirectional;
    return makeIntegrator("vcm", scene, settings);
  }
  return makeIntegrator(name, scene, settings);
}

}  // namespace kasha::test
