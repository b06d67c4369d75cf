#include "integrators/integrator_factory.h"

#include <algorithm>
#include <stdexcept>

#include "scene/wavelength_strategy.h"
#include "integrators/bidirectional/bdpt.h"
#include "integrators/light_tracing/light_tracer.h"
#include "integrators/path_tracing/path_tracer.h"
#include "integrators/photon_mapping/ppm_integrator.h"
#include "integrators/bidirectional/vcm.h"

namespace kasha {
namespace {

// A wavelength site the integrator never draws at must keep its default, so that a strategy
// that was asked for is never silently ignored.
void requireUnused(const WavelengthSpec& spec, const WavelengthSpec& fallback, WavelengthSite site,
                   const std::string& integrator) {
  if (spec.text != fallback.text)
    throw WavelengthStrategyError(site, std::string(settingName(site)) + " '" + spec.text + "' does not apply to the integrator " +
                                integrator + ", which draws no such wavelength (leave it at '" + fallback.text + "')");
}

}  // namespace

std::vector<std::string> integratorNames() { return {"pt", "lt", "bdpt", "bdpt-shared", "bdpt-independent", "bdpt-mollified", "ppm", "vcm", "vc", "bpm"}; }

std::string settingNotRead(const std::string& name, const std::string& key) {
  // The most specific prefix first: ppm's estimators of direct light are its own, its photon pass
  // (count, radius, kernel) is vcm's light-vertex pass too (bidirectional/vcm.cpp).
  static const std::vector<std::pair<std::string, std::vector<std::string>>> readers = {
      {"bdpt_families", {"bdpt"}},
      {"vcm_paths", {"vcm"}},
      {"mollify", {"bdpt-mollified"}},
      {"ppm.direct", {"ppm"}},
      {"ppm.nee_wavelengths", {"ppm"}},
      {"ppm.always_wavelength_kernel", {"ppm"}},
      {"ppm", {"ppm", "vcm", "vc", "bpm"}},
  };
  for (const auto& [prefix, names] : readers) {
    if (key != prefix && key.rfind(prefix + ".", 0) != 0) continue;
    if (std::find(names.begin(), names.end(), name) != names.end()) return {};
    std::string list;
    for (const std::string& n : names) list += (list.empty() ? "" : ", ") + n;
    return "only for --integrator " + list;
  }
  return {};
}

int defaultLanes(const std::string& name, const RenderSettings& s) {
  if (name == "lt") return kDefaultLanes;
  // The camera lanes of pt and ppm need one sensor density and the event's own excitation for NEE.
  if ((name == "pt" || name == "ppm") && s.wavelengths.sensor.isDensity() && s.wavelengths.nee.uses(WavelengthSpec::Kind::Event))
    return kDefaultLanes;
  return 1;
}

std::unique_ptr<Integrator> makeIntegrator(const std::string& name, const Scene& scene, const RenderSettings& requested) {
  RenderSettings s = requested;
  const WavelengthSettings& w = s.wavelengths;
  const WavelengthSettings defaults;
  const bool mollified = name == "bdpt-mollified";
  const bool vcm = name == "vcm" || name == "vc" || name == "bpm";
  const bool bdpt = name == "bdpt" || name == "bdpt-independent" || name == "bdpt-shared" || mollified || vcm;
  if (s.heroWavelengths == kAutoLanes && !bdpt) s.heroWavelengths = defaultLanes(name, s);
  if (s.fluorescentLanes == FluorescentLanes::End && name != "pt" && name != "lt")
    throw FluorescentLanesError("fluorescent_lanes 'end' is an experiment of pt and lt, not of " + name +
                                (bdpt ? " (its lanes end at fluorescent vertices already)"
                                      : " (its camera lanes go through fluorescent events; leave it at 'through')"));
  if (name == "pt") {
    requireUnused(w.light, defaults.light, WavelengthSite::LightStart, name);
    return std::make_unique<PathTracer>(scene, s);  // checks its strategies and lanes
  }
  if (name == "ppm") return std::make_unique<PpmIntegrator>(scene, s);  // checks its strategies and lanes
  if (name != "lt" && !bdpt) {
    std::string known;
    for (const std::string& n : integratorNames()) known += (known.empty() ? "" : ", ") + n;
    throw std::invalid_argument("unknown integrator '" + name + "' (" + known + ")");
  }
  // Only the camera paths of pt and ppm override the material's sampling at fluorescent events
  // (BDPT's reverse densities and the light paths use the material's own).
  requireUnused(w.fluorescence, defaults.fluorescence, WavelengthSite::Fluorescence, name);
  requireUnused(w.nee, defaults.nee, WavelengthSite::Nee, name);
  if (name == "lt") {
    requireUnused(w.sensor, defaults.sensor, WavelengthSite::Sensor, name);
    return std::make_unique<LightTracer>(scene, s);
  }
  if (vcm) {
    const Vcm::Parts parts = name == "vc" ? Vcm::Parts::Connections : name == "bpm" ? Vcm::Parts::Merges
                                                                                  : Vcm::Parts::ConnectionsAndMerges;
    return std::make_unique<Vcm>(scene, s, parts);
  }
  // Every other name is a BDPT's (unknown ones were refused above).
  if (name == "bdpt-shared") requireUnused(w.light, defaults.light, WavelengthSite::LightStart, name);
  const bidir::WavelengthMode mode = name == "bdpt-shared" ? bidir::WavelengthMode::Shared
                                    : name == "bdpt"      ? bidir::WavelengthMode::Unified
                                                          : bidir::WavelengthMode::Independent;
  return std::make_unique<Bdpt>(scene, s, mode, mollified ? &s.mollify : nullptr);
}

}  // namespace kasha
