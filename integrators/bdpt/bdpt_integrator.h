#pragma once
// Bidirectional path tracing for bispectral scenes (docs/bdpt-mis.md): every (s, t) strategy,
// densities both ways, every wavelength density in the MIS weights, and the two exact wavelength
// families of transport.md §3 — light subpaths sharing the camera sample's wavelength (Shared) or
// drawing their own from the lights' power spectrum (Independent), the latter joined through a
// connection vertex that evaluates its fluorescent lobe.
#include "core/sensor_sampling.h"
#include "integrators/bdpt/subpaths.h"
#include "integrators/integrator.h"

namespace kasha {

class Bdpt final : public Integrator {
 public:
  Bdpt(const Scene& scene, SensorSampling sensor, bdpt::WalkSettings settings);
  Vec3 samplePixel(const Scene& scene, Vec2 pixel, Rng& rng, SampleContext& ctx) const override;
  std::string name() const override;

 private:
  SensorWavelengths sensor_;
  bdpt::WalkSettings ws_;
};

}  // namespace kasha
