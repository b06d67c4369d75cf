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

std::vector<std::string> integratorNames() { return {"pt", "lt", "bdpt", "ppm", "vcm", "vc", "bpm"}; }

std::string integratorNameError(const std::string& name) {
  const std::vector<std::string> names = integratorNames();
  if (std::find(names.begin(), names.end(), name) != names.end()) return {};
  for (const IntegratorAlias& alias : integratorAliases())
    if (alias.name == name) return {};
  std::string list;
  for (const std::string& n : names) list += (list.empty() ? "" : ", ") + n;
  return "unknown integrator '" + name + "' (" + list + ")";
}

const std::vector<IntegratorAlias>& integratorAliases() {
  static const std::vector<IntegratorAlias> aliases = {
      {"bdpt-shared", "bdpt", {"bdpt.families=shared"}, [](RenderSettings& s) { s.bdpt.families = BdptFamilies::Shared; }},
      {"bdpt-independent", "bdpt", {"bdpt.families=own"}, [](RenderSettings& s) { s.bdpt.families = BdptFamilies::Own; }},
      {"bdpt-mollified", "bdpt", {"bdpt.families=own", "bdpt.mollify=true"},
       [](RenderSettings& s) { s.bdpt.families = BdptFamilies::Own, s.bdpt.mollify = true; }},
  };
  return aliases;
}

std::string resolveIntegrator(const std::string& name, RenderSettings& s) {
  for (const IntegratorAlias& alias : integratorAliases()) {
    if (alias.name != name) continue;
    alias.apply(s);
    return alias.integrator;
  }
  return name;
}

std::string settingNotRead(const std::string& alias, const std::string& key) {
  RenderSettings unused;
  const std::string name = resolveIntegrator(alias, unused);
  // The most specific prefix first.
  static const std::vector<std::pair<std::string, std::vector<std::string>>> readers = {
      {"bdpt", {"bdpt"}},
      {"vcm.paths", {"vcm"}},
      {"vcm.photons_per_pass", {"vcm", "vc", "bpm"}},
      {"vcm", {"vcm", "bpm"}},  // the radius and the wavelength kernel of the merges
      {"ppm", {"ppm"}},
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

std::unique_ptr<Integrator> makeIntegrator(const std::string& alias, const Scene& scene, const RenderSettings& requested) {
  RenderSettings s = requested;
  const std::string name = resolveIntegrator(alias, s);
  const WavelengthSettings& w = s.wavelengths;
  const WavelengthSettings defaults;
  const bool vcm = name == "vcm" || name == "vc" || name == "bpm";
  const bool bdpt = name == "bdpt" || vcm;
  if (s.heroWavelengths == kAutoLanes && !bdpt) s.heroWavelengths = defaultLanes(name, s);
  if (s.fluorescentLanes == FluorescentLanes::End && name != "pt" && name != "lt")
    throw FluorescentLanesError("fluorescent_lanes 'end' is an experiment of pt and lt, not of " + name +
                                (bdpt ? " (its lanes end at fluorescent vertices already)"
                                      : " (its camera lanes go through fluorescent events; leave it at 'through')"));
  if (name == "pt") {
    requireUnused(w.light, defaults.light, WavelengthSite::LightStart, name);
    return std::make_unique<PathTracer>(scene, s);  // checks its strategies and lanes
  }
  // Merges in media happen only where their sphere meets no surface (docs/media.md §6): merges
  // alone miss the light of collisions near a surface.
  if (scene.hasMedia() && name == "bpm")
    throw std::invalid_argument("bpm does not transport participating media (merges alone cannot reach collisions "
                                "near a surface; vcm and vc do)");
  if (name == "ppm") return std::make_unique<PpmIntegrator>(scene, s);  // checks its strategies and lanes
  if (name != "lt" && !bdpt) throw std::invalid_argument(integratorNameError(name));
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
  // The shared family alone draws no light-start wavelength.
  if (s.bdpt.families == BdptFamilies::Shared) requireUnused(w.light, defaults.light, WavelengthSite::LightStart, "bdpt with families \"shared\"");
  return std::make_unique<Bdpt>(scene, s);
}

}  // namespace kasha
