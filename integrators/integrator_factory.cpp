#include "integrators/integrator_factory.h"

#include <stdexcept>

#include "integrators/light_tracer.h"
#include "integrators/path_tracer.h"

namespace kasha {

std::vector<std::string> integratorNames() { return {"pt", "lt"}; }

std::unique_ptr<Integrator> makeIntegrator(const std::string& name, const Scene& scene, const RenderSettings& s) {
  if (name == "pt") return std::make_unique<PathTracer>(scene, s.sensor, s.maxDepth, s.rrDepth);
  if (name == "lt") return std::make_unique<LightTracer>(s.maxDepth, s.rrDepth);
  std::string known;
  for (const std::string& n : integratorNames()) known += (known.empty() ? "" : ", ") + n;
  throw std::invalid_argument("unknown integrator '" + name + "' (" + known + ")");
}

}  // namespace kasha
