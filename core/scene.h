#pragma once
// A loaded scene: immutable after loading; integrators only read it.
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "core/accel.h"
#include "core/camera.h"
#include "core/light.h"
#include "core/memory_budget.h"
#include "core/wavelength_spec.h"
#include "core/shape.h"
#include "materials/material.h"

namespace kasha {

// Progressive photon mapping (integrator "ppm", docs/photon-mapping.md); zeros are derived from
// the scene.
struct PhotonMappingSettings {
  int photonsPerPass = 0;      // light subpaths per pass; 0: one per pixel
  float radius = 0.0f;         // gather radius r_1 of the first pass, scene units; 0: from the surface area
  float alpha = 2.0f / 3.0f;   // radius reduction (Knaus & Zwicker 2011 eq. 15), in (1/3, 1)
  float bandwidth = 0.0f;      // half-width h_1 of the elastic wavelength kernel, nm; 0: 1% of the range
  bool alwaysKernel = false;   // elastic lobe through the kernel even where the sensor is evaluated exactly
};

// Spectral mollification of BDPT's elastic connections (integrator "bdpt-mollified",
// docs/bdpt-mis.md §6); a zero bandwidth is derived from the scene.
struct MollificationSettings {
  float bandwidth = 0.0f;     // half-width h_1 of the wavelength kernel in the first pass, nm; 0: 2% of the range
  float alpha = 2.0f / 3.0f;  // h_i² = h_{i−1}²·(i − 1 + α)/i (the PPM radius schedule), in (0, 1)
};

// Wavelength sampling strategies per site (docs/wavelength-sampling.md).
struct WavelengthSettings {
  WavelengthSpec sensor = parseWavelengthSpec("cmf");                // the camera's wavelength
  WavelengthSpec fluorescence = parseWavelengthSpec("material");     // λ_i at a camera path's fluorescent event (pt)
  WavelengthSpec light = parseWavelengthSpec("light");               // a light subpath's wavelength (lt, bdpt, ppm)
  WavelengthSpec nee = parseWavelengthSpec("event");                 // λ_i of next-event estimation at a fluorescent event (pt)
};

struct RenderSettings {
  int spp = 16;                 // samples per pixel (a stop condition)
  double timeBudgetSeconds = 0; // > 0: also stop after this long (whole passes only)
  int maxDepth = 64;            // maximum number of scattering events on a path
  int rrDepth = 3;              // Russian roulette from this depth on
  uint64_t seed = 1;
  WavelengthSettings wavelengths;
  int heroWavelengths = 1;      // > 1: hero wavelength sampling with this many wavelengths per path (pt)
  // Largest buffer an integrator may allocate (photon maps, ...): check with requireMemory()
  // before allocating. Set by `kasha render --memory-limit`; not a scene-file setting.
  uint64_t memoryLimit = kDefaultMemoryLimit;
  PhotonMappingSettings ppm;
  MollificationSettings mollify;
};

struct Scene {
  std::string path;  // the scene file
  WavelengthRange range;
  Camera camera;
  RenderSettings render;
  std::vector<std::string> materialNames;
  std::vector<std::unique_ptr<Material>> materials;
  std::vector<Shape> shapes;
  std::vector<std::unique_ptr<Light>> lights;
  std::vector<int> shapeLight;        // index into lights per shape, or −1
  int environmentLight = -1;          // index into lights, or −1
  std::unique_ptr<Accel> accel;
  std::unique_ptr<LightSelector> lightSelector;

  // Texture coordinates of a hit (Shape::surfaceUv).
  Vec2 uv(const Hit& h) const { return shapes[h.shape].surfaceUv(h.prim, h.bary, h.ng); }
  // The scattering function at a hit for a path carrying `wavelengths` there (Material::bsdf).
  Bsdf bsdf(const Hit& h, std::span<const float> wavelengths) const {
    const Material& m = *materials[shapes[h.shape].material];
    const Frame frame = Frame::fromNormal(h.ng);
    return m.bsdf(HitContext{m.textured() ? uv(h) : Vec2(0.0f), frame, frame, wavelengths});
  }
  const EnvironmentLight* environment() const {
    return environmentLight < 0 ? nullptr : static_cast<const EnvironmentLight*>(lights[size_t(environmentLight)].get());
  }
};

}  // namespace kasha
