#include "integrators/integrator_factory.h"

#include <stdexcept>

#include "integrators/bdpt/bdpt_integrator.h"
#include "integrators/light_tracer.h"
#include "integrators/path_tracer.h"
#include "integrators/photon_mapping/ppm_integrator.h"

namespace kasha {

std::vector<std::string> integratorNames() { return {"pt", "lt", "bdpt", "bdpt-shared", "bdpt-independent", "bdpt-mollified", "ppm"}; }

std::unique_ptr<Integrator> makeIntegrator(const std::string& name, const Scene& scene, const RenderSettings& s) {
  if (name == "pt") return std::make_unique<PathTracer>(scene, s.sensor, s.maxDepth, s.rrDepth);
  if (name == "lt") return std::make_unique<LightTracer>(s.maxDepth, s.rrDepth);
  if (name == "bdpt" || name == "bdpt-independent" || name == "bdpt-shared") {
    const bdpt::WavelengthMode mode =
        name == "bdpt-shared" ? bdpt::WavelengthMode::Shared : bdpt::WavelengthMode::Independent;
    return std::make_unique<Bdpt>(scene, s.sensor, bdpt::WalkSettings{s.maxDepth, s.rrDepth, mode});
  }
  if (name == "bdpt-mollified")
    return std::make_unique<Bdpt>(scene, s.sensor, bdpt::WalkSettings{s.maxDepth, s.rrDepth, bdpt::WavelengthMode::Independent},
                                  &s.mollify);
  if (name == "ppm") return std::make_unique<PpmIntegrator>(scene, s);
  std::string known;
  for (const std::string& n : integratorNames()) known += (known.empty() ? "" : ", ") + n;
  throw std::invalid_argument("unknown integrator '" + name + "' (" + known + ")");
}

}  // namespace kasha
