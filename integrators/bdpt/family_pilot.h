#pragma once
// The pilot that chooses the unified bdpt's light subpaths per scene (docs/bdpt-mis.md §13): two
// estimators of every pixel from the same camera samples, two independent images of each, and each
// estimator's relative variance per sample over the image.
#include <cstdint>
#include <functional>
#include <utility>

#include "core/sampler.h"
#include "integrators/integrator.h"

namespace kasha::bdpt {

// One camera sample through `pixel` (its integer corner) estimated twice: estimator a writes its
// splats to `a`, estimator b to `b`; returns the two camera-sample values. `excess` receives, per
// pixel, what b's second moment has over a's from this sample's paths (Splat::xyz per channel).
using PilotSample = std::function<std::pair<Vec3, Vec3>(Vec2 pixel, Sampler& rng, SampleContext& a, SampleContext& b,
                                                        std::vector<Splat>& excess)>;

struct PilotVariances {
  double a = 0.0, b = 0.0;  // each estimator's relative variance per sample
  // b's relative variance per sample less a's, from the excess second moments: the mean over the
  // pixels of Σ_XYZ e / (m² + 10⁻²), e the pixel's excess per sample.
  double excess = 0.0;
  // Whether the two estimators' images agree in every 16×16 region and channel within 5 standard
  // errors (from the per-sample variances). Both are unbiased, so a larger difference means one of
  // them missed light that is rare under it, and its variance above is an underestimate.
  bool agree = true;
  RayCounter rays;  // traced by the pilot
};

// Each image takes n = ⌈16384 / pixels⌉ samples per pixel (1 from 128 × 128 on). For each
// estimator, the mean over the pixels of Σ_XYZ v / (m² + 10⁻²): v = n·(x₁ − x₂)²/2, the per-sample
// variance from its two images, and m the 5×5 box mean of all four images (the relative
// error of integrators/comparison.h with a smooth stand-in for the reference). The 0.01% largest
// pixels of each estimator are left out, so that one outlier does not decide. Pixels whose value is
// not finite count as 0. Random numbers: `kind` with a seed of its own derived from `seed`.
PilotVariances pilotVariances(int width, int height, uint64_t seed, SamplerKind kind, const PilotSample& sample);

}  // namespace kasha::bdpt
