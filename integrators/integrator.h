#pragma once
// An integrator estimates the XYZ value of one pixel sample. The render loop (render_loop.h) owns
// threads, seeds and the film; integrators are stateless and read-only on the scene.
#include <cstdint>
#include <string>
#include <vector>

#include "core/math.h"
#include "core/rng.h"
#include "core/scene.h"

namespace kasha {

struct RayCounter {
  uint64_t closest = 0;  // closest-hit queries
  uint64_t shadow = 0;   // occlusion queries
};

// A contribution to another pixel than the one being sampled (light tracing, BDPT's t = 1).
struct Splat {
  Vec2 pixel;
  Vec3 xyz;
};

// What a pixel sample may write besides its return value.
struct SampleContext {
  RayCounter counter;
  std::vector<Splat> splats;  // merged into the film in a fixed order after each pass
};

class Integrator {
 public:
  virtual ~Integrator() = default;
  // One estimate of the pixel's XYZ (the film normalisation of core/color.h) through the
  // continuous film position `pixel` (its integer corner; the integrator jitters). Contributions
  // to other pixels go to ctx.splats, in units where the film divides by samples per pixel.
  virtual Vec3 samplePixel(const Scene& scene, Vec2 pixel, Rng& rng, SampleContext& ctx) const = 0;
  virtual std::string name() const = 0;
};

}  // namespace kasha
