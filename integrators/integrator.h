#pragma once
// An integrator estimates the XYZ value of one pixel sample. The render loop (render_loop.h) owns
// threads, seeds and the film; integrators are stateless and read-only on the scene. State built
// once per pass (photon mapping's photon map) is returned by beginPass and read through the
// SampleContext, never stored in the integrator.
#include <cstdint>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "core/color.h"
#include "core/math.h"
#include "core/sampler.h"
#include "scene/scene.h"

namespace kasha {

struct RayCounter {
  uint64_t closest = 0;  // closest-hit queries
  uint64_t shadow = 0;   // occlusion queries
};

// A contribution to another pixel than the one being sampled (light tracing, BDPT's t = 1):
// xyz = W(λ)·value (core/color.h), value being what the spectral bins receive at lambda.
struct Splat {
  Vec2 pixel;
  Vec3 xyz;
  float lambda = 0.0f, value = 0.0f;
};
// The splat of `value` (radiance over the wavelength density, in the units of a splat) at λ.
inline Splat spectralSplat(Vec2 pixel, float lambda, float value) {
  return {pixel, Observer::cie1931().weight(lambda) * value, lambda, value};
}

// One wavelength's share of a camera sample, for spectral bins (core/spectral_film.h).
struct SpectralSample {
  float lambda = 0.0f, value = 0.0f;
};

// One strategy's share of a sample, recorded when SampleContext::recordStrategies is set (BDPT's
// per-strategy images): XYZ in the units of a splat, with and without its MIS weight.
struct StrategySample {
  Vec2 pixel;
  Vec3 weighted, unweighted;
  int s = 0, t = 0;
  uint8_t variant = 0;  // the integrator's own strategy variant (BDPT: bidir::Variant)
};

// What an integrator prepares before a pass and its samples only read (a photon map).
struct PassData {
  virtual ~PassData() = default;
};

// What a pixel sample may write besides its return value.
struct SampleContext {
  RayCounter counter;
  std::vector<Splat> splats;  // merged into the film in a fixed order after each pass
  const PassData* pass = nullptr;  // what beginPass returned for the current pass
  bool recordStrategies = false;   // integrators that can, append to `strategies`
  std::vector<StrategySample> strategies;  // merged in a fixed order after each pass, like splats
  bool recordSpectral = false;             // set when the render keeps spectral bins
  std::vector<SpectralSample> spectral;    // this camera sample's shares, read after each sample
};

// The XYZ of radiance-over-density `value` arriving at the sensor at λ, W(λ)·value (core/color.h),
// recorded for the spectral bins when the render keeps them. Every camera-sample contribution of
// an integrator goes through here.
// With the observer's weight at lambda already known (`response`).
inline Vec3 sensorResponse(SampleContext& ctx, float lambda, Vec3 response, float value) {
  if (ctx.recordSpectral) ctx.spectral.push_back({lambda, value});
  return response * value;
}
inline Vec3 sensorResponse(SampleContext& ctx, float lambda, float value) {
  return sensorResponse(ctx, lambda, Observer::cie1931().weight(lambda), value);
}

// What an integrator can do besides estimating pixels: the render job (render_job.h) asks it here,
// never by its type, before it accepts a render's options.
struct Capabilities {
  int lanes = 1;                // wavelengths each path carries (Integrator::lanes)
  bool strategyImages = false;  // records each (s, t) strategy's share (SampleContext::recordStrategies)
  bool spectralBins = true;     // reports its samples' spectral shares (SampleContext::recordSpectral)
};

class Integrator {
 public:
  virtual ~Integrator() = default;
  // One estimate of the pixel's XYZ (the film normalisation of core/color.h); `pixel` is its
  // integer corner, and the integrator draws the film position from the scene's reconstruction
  // filter (PixelFilter::filmPosition). Contributions to other pixels go to ctx.splats, in units
  // where the film divides by samples per pixel.
  virtual Vec3 samplePixel(const Scene& scene, Vec2 pixel, Sampler& rng, SampleContext& ctx) const = 0;
  virtual std::string name() const = 0;
  // Wavelengths each path carries (wavelength lanes; 1 without them).
  virtual int lanes() const { return 1; }
  // Every integrator keeps spectral bins (docs/cli.md, `--spectral-bins`); only the bidirectional
  // engine's have (s, t) strategies.
  virtual Capabilities capabilities() const { return {lanes(), false, true}; }

  // Called by the render loop before each pass, which takes samples [firstSample, firstSample +
  // count) of every pixel; seed is the render's seed. Rays traced here count in `counter`. The
  // result stays alive and unchanged while the pass runs (SampleContext::pass).
  virtual std::unique_ptr<const PassData> beginPass(const Scene& scene, int firstSample, int count, uint64_t seed,
                                                    RayCounter& counter) const {
    return nullptr;
  }
  // What the integrator decided for the render so far (a pilot's choice), for its statistics;
  // empty if nothing.
  virtual std::string choices() const { return {}; }
  // The most samples per pixel one pass may take.
  virtual int maxSamplesPerPass() const { return std::numeric_limits<int>::max(); }
};

}  // namespace kasha
