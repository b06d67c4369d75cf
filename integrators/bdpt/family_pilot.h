#pragma once
// The pilot that chooses the unified bdpt's light subpaths per scene (docs/bdpt-mis.md §13): two
// independent images of an estimator, its relative variance per sample over the image, and what
// an alternative estimator would add to it, from the estimator's own paths.
#include <cstdint>
#include <functional>
#include <vector>

#include "core/sampler.h"
#include "integrators/integrator.h"

namespace kasha::bdpt {

// One camera sample through `pixel` (its integer corner): returns its value, writes its splats to
// ctx and appends to `excess`, per pixel, what the alternative's second moment has over the
// estimator's from this sample's paths (Splat::xyz per channel).
using PilotSample = std::function<Vec3(Vec2 pixel, Sampler& rng, SampleContext& ctx, std::vector<Splat>& excess)>;

struct PilotEstimates {
  double relVar = 0.0;     // the estimator's relative variance per sample
  double relExcess = 0.0;  // what the alternative's has over it
  RayCounter rays;         // traced by the pilot
};

// Each image takes n = ⌈16384 / pixels⌉ samples per pixel (1 from 128 × 128 on). relVar is the mean
// over the pixels of Σ_XYZ v / (m² + 10⁻²): v = n·(x₁ − x₂)²/2, the per-sample variance from the
// two images, and m the 5×5 box mean of both (the relative error of integrators/comparison.h with
// a smooth stand-in for the reference); the 0.01% largest pixels are left out, so that one outlier
// does not decide. relExcess is the mean over the pixels of Σ_XYZ e / (m² + 10⁻²), e the pixel's
// excess per sample. Values that are not finite count as 0. Random numbers: `kind` with a seed of
// their own derived from `seed`.
PilotEstimates pilotEstimates(int width, int height, uint64_t seed, SamplerKind kind, const PilotSample& sample);

}  // namespace kasha::bdpt
