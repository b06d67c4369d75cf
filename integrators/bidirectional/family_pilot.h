#pragma once
// The pilot that chooses the unified bdpt's light subpaths per scene (docs/bdpt-mis.md §13): two
// independent images of an estimator, its relative variance per sample over the image, what each
// alternative estimator would add to it, from the estimator's own paths, and the rays per sample of
// an estimator.
#include <cstdint>
#include <functional>
#include <vector>

#include "core/sampler.h"
#include "integrators/integrator.h"

namespace kasha::bidir {

// One camera sample through `pixel` (its integer corner): returns its value, writes its splats to
// ctx and appends to excess[a], per pixel, what alternative a's second moment has over the
// estimator's from this sample's paths (Splat::xyz per channel).
using PilotSample =
    std::function<Vec3(Vec2 pixel, Sampler& rng, SampleContext& ctx, std::vector<std::vector<Splat>>& excess)>;

struct PilotEstimates {
  double relVar = 0.0;             // the estimator's relative variance per sample
  std::vector<double> relExcess;   // per alternative, what its relative variance has over relVar
  RayCounter rays;                 // traced by the pilot
  size_t samples = 0;              // camera samples it took
};

// The image is cut into cells of qx × qy pixels, with r = pixels / 8192, qy = ⌊√r⌋ and
// qx = ⌊r / qy⌋ (at least 1 each), each sampled at its centre pixel (splats land in the cell that
// holds them: a cell's sum then has the mean and variance of one pixel's splats at full
// resolution); each image takes n = ⌈8192 / cells⌉ samples per cell.
// relVar is the mean over the cells of Σ_XYZ v / (m² + 10⁻²): v = n·(x₁ − x₂)²/2, the per-sample
// variance from the two images, and m the mean of both over the 5×5 cells around the cell, the cell
// itself left out (the relative error of integrators/comparison.h with a smooth stand-in for the
// reference that is independent of v); the 0.01% largest cells are
// left out, so that one outlier does not decide. relExcess[a] is the mean over the cells of
// Σ_XYZ e / (m² + 10⁻²), e the cell's excess per sample for alternative a. Values that are not finite
// count as 0. Random numbers: `kind` with a seed of their own derived from `seed`.
// `passes`: empty, or one per sample of a cell, pilotSamplesPerImage(width, height) for each image
// (image 0's first): sample j of image i reads passes[i·n + j] as ctx.pass, so that an estimator
// whose samples share what a pass prepared (vertex merging's light vertices) has that sharing's
// variance in the difference of the two images, as its passes have in a render (one per sample
// per pixel).
PilotEstimates pilotEstimates(int width, int height, uint64_t seed, SamplerKind kind, int alternatives,
                              const PilotSample& sample, const std::vector<const PassData*>& passes = {});

// n, the samples per cell of each of pilotEstimates' images.
int pilotSamplesPerImage(int width, int height);

// `pixels` pixels (at most width × height) spread evenly over the image: the centres of a grid of
// about square cells, row by row (their integer corners).
std::vector<Vec2> spreadPixels(int width, int height, size_t pixels);

// The relative variance per sample of an estimator whose samples do not splat, at `spp` samples per
// pixel: two independent images (random numbers of `kind`, each image with a seed of its own derived
// from `seed`) at `pixels` pixels spread evenly over the image (spreadPixels), the mean over the pixels of
// Σ_XYZ spp·(x₁ − x₂)²/2 / (m² + 10⁻²), m the mean of the two. With a sampler that stratifies the
// samples of a pixel (Sobol) it shows what the stratification gains at that count. The rays traced
// are added to `rays`.
double relativeVarianceAtPixels(int width, int height, uint64_t seed, SamplerKind kind, int spp, size_t pixels,
                                const PilotSample& sample, RayCounter& rays);

// The rays `count` camera samples of `sample` trace, at pixels spread evenly over the image, with
// random numbers of their own derived from `seed`.
RayCounter raysOfSamples(int width, int height, uint64_t seed, SamplerKind kind, size_t count, const PilotSample& sample);

// An alternative estimator's cost per sample in rays, from 1024 samples of its own (raysOfSamples,
// independent numbers), whose rays are added to `counter`.
double raysPerSample(int width, int height, uint64_t seed, const PilotSample& sample, RayCounter& counter);

}  // namespace kasha::bidir
