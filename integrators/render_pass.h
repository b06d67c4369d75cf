#pragma once
// One render pass: samples [first, first + count) of every pixel, traced into a PassRecord and
// then committed to the film. Tracing and committing are apart so that a pass may be traced by
// another process (render_group.h) and still reach the film in exactly the order of a
// one-process render: a pixel's camera samples in sample order, splats and strategy records in
// tile order, the passes in pass order.
#include <cstdint>
#include <functional>
#include <vector>

#include "core/film.h"
#include "core/spectral_film.h"
#include "integrators/integrator.h"

namespace kasha {

// What one pass produced, before it reaches the film. Plain data, so it can be sent as bytes.
struct PassRecord {
  int first = 0, count = 0;   // the samples of every pixel this pass took
  std::vector<Vec3> samples;  // row-major pixels, `count` consecutive values each, in sample order
  std::vector<Splat> splats;  // in tile order
  std::vector<StrategySample> strategies;  // in tile order (only when recording strategies)
  // Only when recording spectral shares: how many shares each sample of `samples` has (same
  // layout), and the shares themselves, in the order of the samples in tile order.
  std::vector<uint32_t> spectralCounts;
  std::vector<SpectralSample> spectral;
  RayCounter rays;            // traced by the pass (Integrator::beginPass and the samples)
};

// Traces passes of one integrator over one image: fixed 16×16 tiles in parallel (TBB). Sample s
// of pixel p draws from the Sampler (kind, seed, p, s) (core/sampler.h), so a record depends only
// on the pass's samples, never on threads, processes or the passes before it.
class PassTracer {
 public:
  PassTracer(const Scene& scene, const Integrator& integrator, int width, int height, uint64_t seed,
             SamplerKind sampler, bool recordStrategies, bool recordSpectral);
  // Traces samples [first, first + count) of every pixel into `rec`, replacing what it held. Its
  // buffers keep their capacity from pass to pass: a new record per pass freed and faulted in
  // megabytes of splats each time (docs/benchmarks.md, "Pass buffers and the heap").
  void trace(int first, int count, PassRecord& rec);
  // Adds a record to the film: each pixel's samples in sample order (pixels in tile order, so the
  // first non-finite pixel is the same as with one thread), then the splats; the spectral shares
  // of the samples and splats the film keeps go to `spectral` if set; strategy records go to
  // `strategies` if set. Records must be committed in pass order for bit-identical sums.
  void commit(const PassRecord& record, Film& film, SpectralFilm* spectral,
              const std::function<void(const StrategySample&)>& strategies) const;

  // Bytes of the sample buffer of a pass of `samplesPerPixel` (a record's splats come on top). With
  // `spectral`, each sample's share count and one share, kept per tile and again in the record;
  // samples with more shares (hero wavelengths, photon mapping's exact elastic gathers) take more.
  static uint64_t sampleBytes(int width, int height, int samplesPerPixel, bool spectral = false);

 private:
  template <class PixelFn>
  void forEachPixelOfTile(int tile, PixelFn&& fn) const;
  const Scene& scene_;
  const Integrator& integrator_;
  int w_, h_, tilesX_, tileCount_;
  uint64_t seedMix_, seed_;
  SamplerKind sampler_;
  bool recordStrategies_, recordSpectral_;
  std::vector<SampleContext> contexts_;  // one per tile, reused across passes
  std::vector<std::vector<SpectralSample>> tileSpectral_;  // each tile's shares, in pixel and sample order
};

}  // namespace kasha
