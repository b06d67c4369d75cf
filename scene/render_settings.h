#pragma once
// Render and integrator settings: read from a scene file's "render" object and the command line,
// used by the integrators.
#include <cstdint>
#include <functional>
#include <optional>
#include <stdexcept>
#include <string>

#include "core/memory_budget.h"
#include "core/sampler.h"
#include "core/wavelength_spec.h"

namespace kasha {

// Which estimator of photon mapping counts light that reaches a camera vertex straight from a
// light (docs/photon-mapping.md §3): next-event estimation for the elastic lobe and photons for the
// fluorescent lobe ("nee-elastic"), next-event estimation for every lobe ("nee"), or photons ("photons").
enum class PpmDirectLight { NeeElastic, Nee, Photons };

inline const char* toString(PpmDirectLight d) {
  return d == PpmDirectLight::Nee ? "nee" : d == PpmDirectLight::Photons ? "photons" : "nee-elastic";
}

// The light-vertex pass and the progressive radius shared by photon mapping and vertex merging;
// zeros are derived from the scene.
struct ProgressiveSettings {
  int photonsPerPass = 0;      // light subpaths per pass; 0: one per pixel
  float radius = 0.0f;         // gather radius r_1 of the first pass, scene units; 0: from the scene
  float alpha = 2.0f / 3.0f;   // radius reduction (Knaus & Zwicker 2011 eq. 15), in (1/3, 1)
  float bandwidth = 0.0f;      // half-width h_1 of the elastic wavelength kernel, nm; 0: 1% of the range
  // Radius of the first pass's merges or gathers at collisions in media, scene units; 0: from the
  // scene (ppm: r_1/4, docs/photon-mapping.md §9; vcm: a sphere holds about one light vertex,
  // counted on a pilot, docs/media.md §6). It shrinks by the three-dimensional schedule.
  float volumeRadius = 0.0f;
};

// Progressive photon mapping, render/ppm (integrator "ppm", docs/photon-mapping.md).
struct PhotonMappingSettings : ProgressiveSettings {
  bool alwaysKernel = false;   // elastic lobe through the kernel even where the sensor is evaluated exactly
  PpmDirectLight direct = PpmDirectLight::NeeElastic;
  // The wavelengths of next-event estimation's elastic lobe at the first camera vertex, where the
  // sensor can be evaluated at any wavelength (docs/photon-mapping.md §3): "cmf*light" (lanes of
  // their own, a third of the density for each of x̄·Σ_l Φ_l, ȳ·Σ_l Φ_l, z̄·Σ_l Φ_l, with a
  // defensive colour-matching share), "camera" (the camera path's lanes), or a wavelength strategy
  // that is one density ("mix:cmf,light", ...).
  std::string neeWavelengths = "cmf*light";
};

// Why `text` is not a value of render/ppm/nee_wavelengths, or an empty string if it is one.
inline std::string ppmNeeWavelengthsError(const std::string& text) {
  if (text == "camera" || text == "cmf*light") return {};
  try {
    if (!parseWavelengthSpec(text).isDensity()) return "'" + text + "' is not one density (use a single strategy or mix:)";
  } catch (const std::invalid_argument& e) {
    return "expected \"cmf*light\", \"camera\" or a wavelength strategy: " + std::string(e.what());
  }
  return {};
}

// Wavelength sampling strategies per site (docs/wavelength-sampling.md).
struct WavelengthSettings {
  WavelengthSpec sensor = parseWavelengthSpec("cmf");                // the camera's wavelength
  WavelengthSpec fluorescence = parseWavelengthSpec("material");     // λ_i at a camera path's fluorescent event (pt)
  WavelengthSpec light = parseWavelengthSpec("light");               // a light subpath's wavelength (lt, bdpt, ppm)
  WavelengthSpec nee = parseWavelengthSpec("event");                 // λ_i of next-event estimation at a fluorescent event (pt)
};

// What wavelength lanes do at a vertex that takes the fluorescent lobe (docs/wavelength-sampling.md
// "Lanes through fluorescent events"): go on through it (a fresh set serves every lane before it),
// or end in one lane chosen at random, as ART, Mojzík et al. and pbrt-style renderers do (an
// experiment to compare with; pt and lt).
enum class FluorescentLanes { Through, End };

inline const char* toString(FluorescentLanes f) { return f == FluorescentLanes::End ? "end" : "through"; }
// "through" or "end"; nullopt otherwise.
inline std::optional<FluorescentLanes> parseFluorescentLanes(const std::string& text) {
  if (text == "through") return FluorescentLanes::Through;
  if (text == "end") return FluorescentLanes::End;
  return std::nullopt;
}

// Which light subpaths `bdpt` traces (docs/bdpt-mis.md §13): both families (in a scene that
// fluoresces; else the shared one), the shared family alone, the own family alone, or (auto, the
// default) whichever a pilot estimates the most efficient where the scene fluoresces.
enum class BdptFamilies { Auto, Both, Shared, Own };

inline const char* toString(BdptFamilies f) {
  switch (f) {
    case BdptFamilies::Both: return "both";
    case BdptFamilies::Shared: return "shared";
    case BdptFamilies::Own: return "own";
    default: return "auto";
  }
}
// "auto", "both", "shared" or "own"; nullopt otherwise.
inline std::optional<BdptFamilies> parseBdptFamilies(const std::string& text) {
  if (text == "auto") return BdptFamilies::Auto;
  if (text == "both") return BdptFamilies::Both;
  if (text == "shared") return BdptFamilies::Shared;
  if (text == "own") return BdptFamilies::Own;
  return std::nullopt;
}

// Which subpaths `vcm` traces (docs/bdpt-mis.md §14): camera and light subpaths with every strategy
// (bidirectional), the same with photon mapping's wide final gather (gather: own light vertices
// merge through a fluorescent lobe at the first non-specular camera vertex within 4× the radius),
// camera and light subpaths with the connections alone (connections: `vc`'s estimator), camera
// subpaths alone (camera: vertex connection and merging without light subpaths is path tracing with
// next-event estimation, and runs pt's estimator), or (auto, the default) whichever a pilot
// estimates the most efficient.
enum class VcmPaths { Auto, Bidirectional, Gather, Connections, Camera };

inline const char* toString(VcmPaths p) {
  switch (p) {
    case VcmPaths::Bidirectional: return "bidirectional";
    case VcmPaths::Gather: return "gather";
    case VcmPaths::Connections: return "connections";
    case VcmPaths::Camera: return "camera";
    default: return "auto";
  }
}
// "auto", "bidirectional", "gather", "connections" or "camera"; nullopt otherwise.
inline std::optional<VcmPaths> parseVcmPaths(const std::string& text) {
  if (text == "auto") return VcmPaths::Auto;
  if (text == "bidirectional") return VcmPaths::Bidirectional;
  if (text == "gather") return VcmPaths::Gather;
  if (text == "connections") return VcmPaths::Connections;
  if (text == "camera") return VcmPaths::Camera;
  return std::nullopt;
}

// Bidirectional path tracing, render/bdpt (integrator "bdpt", docs/bdpt-mis.md).
struct BdptSettings {
  BdptFamilies families = BdptFamilies::Auto;
  // Spectral mollification of the own family's elastic connections (docs/bdpt-mis.md §6): a
  // wavelength kernel of half-width h_1 in the first pass (nm; 0: 2% of the range) that shrinks as
  // h_i² = h_{i−1}²·(i − 1 + α)/i (the PPM radius schedule), α in (0, 1).
  bool mollify = false;
  float mollifyBandwidth = 0.0f;
  float mollifyAlpha = 2.0f / 3.0f;
};

// Vertex connection and merging, render/vcm (integrators "vcm", "vc" and "bpm", docs/bdpt-mis.md §12).
struct VcmSettings : ProgressiveSettings {
  VcmPaths paths = VcmPaths::Auto;  // vcm's subpaths
  // Light vertices in homogeneous media also merge with the camera's query beams, within the volume
  // radius across them (photon points against beams, docs/media-beams.md).
  bool beams = true;
  // And, with beams, the light subpaths' flights through homogeneous media (photon beams against the
  // query beams, within a cylinder of the volume radius around each). Off by default: on the media
  // scenes they do not earn their cost (docs/media-beams.md).
  bool photonBeams = false;
};

// The ranges of the integrators' own settings, checked in one place for the scene loader and for
// integrators built from code: `fail(key, reason)` is called for the first field out of range
// (key as in the scene file, "alpha") and must not return.
using SettingFailure = std::function<void(const char* key, const std::string& reason)>;
void checkProgressiveSettings(const ProgressiveSettings& p, const SettingFailure& fail);
void checkBdptSettings(const BdptSettings& b, const SettingFailure& fail);

// Thrown when an integrator cannot do what fluorescent_lanes asks (its message says why).
struct FluorescentLanesError : std::invalid_argument {
  using std::invalid_argument::invalid_argument;
};

inline constexpr int kAutoLanes = 0;
inline constexpr int kDefaultLanes = 4;  // an integrator's lanes where it carries them by default

struct RenderSettings {
  // The integrator the scene asks for (render/integrator; integrators/integrator_factory.h checks
  // the name); the front ends' own choice (--integrator, kasha.render's integrator=) wins.
  std::string integrator = "pt";
  int spp = 16;                 // samples per pixel (a stop condition)
  double timeBudgetSeconds = 0; // > 0: also stop after this long (whole passes only)
  int maxDepth = 64;            // maximum number of scattering events on a path
  int rrDepth = 3;              // Russian roulette from this depth on
  // Paths without a scattering event (emitters seen directly) contribute nothing (Mitsuba's
  // hide_emitters); the rest of the image is unchanged.
  bool hideEmitters = false;
  uint64_t seed = 1;
  SamplerKind sampler = SamplerKind::Sobol;  // random numbers of every sample (core/sampler.h)
  WavelengthSettings wavelengths;
  // Wavelength lanes per path (hero wavelength sampling; pt, lt, bdpt): 1 to 16, or kAutoLanes for the
  // integrator's default (integrators/integrator_factory.h: 4 where the integrator and its
  // wavelength strategies carry lanes, else 1).
  int heroWavelengths = kAutoLanes;
  FluorescentLanes fluorescentLanes = FluorescentLanes::Through;
  // Largest buffer an integrator may allocate (photon maps, ...): check with requireMemory()
  // before allocating. Set by `kasha render --memory-limit`; not a scene-file setting.
  uint64_t memoryLimit = kDefaultMemoryLimit;
  // Each integrator's own settings (render/<integrator>).
  BdptSettings bdpt;
  VcmSettings vcm;
  PhotonMappingSettings ppm;
};

}  // namespace kasha
