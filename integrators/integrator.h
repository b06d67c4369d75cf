#pragma once
// An integrator estimates the XYZ value of one pixel sample. The render loop (render_loop.h) owns
// threads, seeds and the film; integrators are stateless and read-only on the scene.
#include <cstdint>
#include <string>

#include "core/math.h"
#include "core/rng.h"
#include "core/scene.h"

namespace kasha {

struct RayCounter {
  uint64_t closest = 0;  // closest-hit queries
  uint64_t shadow = 0;   // occlusion queries
};

class Integrator {
 public:
  virtual ~Integrator() = default;
  // One estimate of the pixel's XYZ (the film normalisation of core/color.h) through the
  // continuous film position `pixel`.
  virtual Vec3 samplePixel(const Scene& scene, Vec2 pixel, Rng& rng, RayCounter& counter) const = 0;
  virtual std::string name() const = 0;
};

}  // namespace kasha
