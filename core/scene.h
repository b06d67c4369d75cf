#pragma once
// A loaded scene: immutable after loading; integrators only read it.
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "core/accel.h"
#include "core/camera.h"
#include "core/light.h"
#include "core/sensor_sampling.h"
#include "core/shape.h"
#include "materials/material.h"

namespace kasha {

struct RenderSettings {
  int spp = 16;                 // samples per pixel (a stop condition)
  double timeBudgetSeconds = 0; // > 0: also stop after this long (whole passes only)
  int maxDepth = 64;            // maximum number of scattering events on a path
  int rrDepth = 3;              // Russian roulette from this depth on
  uint64_t seed = 1;
  SensorSampling sensor = SensorSampling::ColorMatching;
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

  const Material& material(const Hit& h) const { return *materials[shapes[h.shape].material]; }
  const EnvironmentLight* environment() const {
    return environmentLight < 0 ? nullptr : static_cast<const EnvironmentLight*>(lights[size_t(environmentLight)].get());
  }
};

}  // namespace kasha
