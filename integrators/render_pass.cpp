#include "integrators/render_pass.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

namespace kasha {
namespace {
constexpr int kTile = 16;
}  // namespace

PassTracer::PassTracer(const Scene& scene, const Integrator& integrator, int width, int height, uint64_t seed,
                       SamplerKind sampler, bool recordStrategies)
    : scene_(scene), integrator_(integrator), w_(width), h_(height), tilesX_((width + kTile - 1) / kTile),
      tileCount_(tilesX_ * ((height + kTile - 1) / kTile)), seedMix_(mixBits(seed + 0x9e3779b97f4a7c15ULL)),
      seed_(seed), sampler_(sampler), recordStrategies_(recordStrategies), contexts_(size_t(tileCount_)) {}

uint64_t PassTracer::sampleBytes(int width, int height, int samplesPerPixel) {
  return uint64_t(width) * uint64_t(height) * uint64_t(std::max(samplesPerPixel, 0)) * sizeof(Vec3);
}

template <class PixelFn>
void PassTracer::forEachPixelOfTile(int tile, PixelFn&& fn) const {
  const int x0 = (tile % tilesX_) * kTile, y0 = (tile / tilesX_) * kTile;
  for (int y = y0; y < std::min(y0 + kTile, h_); ++y)
    for (int x = x0; x < std::min(x0 + kTile, w_); ++x) fn(x, y, size_t(y) * size_t(w_) + size_t(x));
}

PassRecord PassTracer::trace(int first, int count) {
  PassRecord rec;
  rec.first = first;
  rec.count = count;
  rec.samples.resize(size_t(w_) * size_t(h_) * size_t(count));
  const std::unique_ptr<const PassData> passData = integrator_.beginPass(scene_, first, count, seed_, rec.rays);
  tbb::parallel_for(tbb::blocked_range<int>(0, tileCount_, 1), [&](const tbb::blocked_range<int>& range) {
    for (int tile = range.begin(); tile < range.end(); ++tile) {
      SampleContext& ctx = contexts_[size_t(tile)];
      ctx.counter = RayCounter{};
      ctx.splats.clear();
      ctx.strategies.clear();
      ctx.recordStrategies = recordStrategies_;
      ctx.pass = passData.get();
      forEachPixelOfTile(tile, [&](int x, int y, size_t pixel) {
        Vec3* out = rec.samples.data() + pixel * size_t(count);
        for (int s = first; s < first + count; ++s) {
          Sampler rng(sampler_, seedMix_, uint64_t(pixel), uint32_t(s));
          out[s - first] = integrator_.samplePixel(scene_, Vec2(float(x), float(y)), rng, ctx);
        }
      });
    }
  }, tbb::simple_partitioner());
  // Gathered in tile order, so the record does not depend on scheduling.
  for (SampleContext& ctx : contexts_) {
    rec.rays.closest += ctx.counter.closest;
    rec.rays.shadow += ctx.counter.shadow;
    rec.splats.insert(rec.splats.end(), ctx.splats.begin(), ctx.splats.end());
    rec.strategies.insert(rec.strategies.end(), ctx.strategies.begin(), ctx.strategies.end());
  }
  return rec;
}

void PassTracer::commit(const PassRecord& rec, Film& film,
                        const std::function<void(const StrategySample&)>& strategies) const {
  for (int tile = 0; tile < tileCount_; ++tile)
    forEachPixelOfTile(tile, [&](int x, int y, size_t pixel) {
      const Vec3* in = rec.samples.data() + pixel * size_t(rec.count);
      for (int i = 0; i < rec.count; ++i) film.add(x, y, in[i]);
    });
  for (const Splat& sp : rec.splats) {
    // A splat at a non-finite position is counted like a non-finite sample (pixel -1, -1).
    if (!std::isfinite(sp.pixel.x) || !std::isfinite(sp.pixel.y)) {
      film.addNonFinite(-1, -1);
      continue;
    }
    // Clamped as floats: converting a huge float to int would be undefined behaviour.
    const int x = int(std::clamp(sp.pixel.x, 0.0f, float(w_ - 1))), y = int(std::clamp(sp.pixel.y, 0.0f, float(h_ - 1)));
    film.addSplat(x, y, sp.xyz);
  }
  if (strategies)
    for (const StrategySample& r : rec.strategies) strategies(r);
}

}  // namespace kasha
