#include "integrators/render_pass.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

#include "core/pixel_filter.h"

namespace kasha {
namespace {
constexpr int kTile = 16;

bool isFinite(const Vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }
}  // namespace

PassTracer::PassTracer(const Scene& scene, const Integrator& integrator, int width, int height, uint64_t seed,
                       SamplerKind sampler, bool recordStrategies, bool recordSpectral)
    : scene_(scene), integrator_(integrator), w_(width), h_(height), tilesX_((width + kTile - 1) / kTile),
      tileCount_(tilesX_ * ((height + kTile - 1) / kTile)), seedMix_(mixBits(seed + 0x9e3779b97f4a7c15ULL)),
      seed_(seed), sampler_(sampler), recordStrategies_(recordStrategies), recordSpectral_(recordSpectral),
      contexts_(size_t(tileCount_)), tileSpectral_(recordSpectral ? size_t(tileCount_) : 0) {}

uint64_t PassTracer::sampleBytes(int width, int height, int samplesPerPixel, bool spectral) {
  const uint64_t perSample = sizeof(Vec3) + (spectral ? sizeof(uint32_t) + 2 * sizeof(SpectralSample) : 0);
  return uint64_t(width) * uint64_t(height) * uint64_t(std::max(samplesPerPixel, 0)) * perSample;
}

template <class PixelFn>
void PassTracer::forEachPixelOfTile(int tile, PixelFn&& fn) const {
  const int x0 = (tile % tilesX_) * kTile, y0 = (tile / tilesX_) * kTile;
  for (int y = y0; y < std::min(y0 + kTile, h_); ++y)
    for (int x = x0; x < std::min(x0 + kTile, w_); ++x) fn(x, y, size_t(y) * size_t(w_) + size_t(x));
}

void PassTracer::trace(int first, int count, PassRecord& rec) {
  rec.first = first;
  rec.count = count;
  rec.rays = RayCounter{};
  rec.samples.resize(size_t(w_) * size_t(h_) * size_t(count));
  rec.splats.clear();
  rec.strategies.clear();
  rec.spectral.clear();
  rec.spectralCounts.resize(recordSpectral_ ? rec.samples.size() : 0);
  const std::unique_ptr<const PassData> passData = integrator_.beginPass(scene_, first, count, seed_, rec.rays);
  tbb::parallel_for(tbb::blocked_range<int>(0, tileCount_, 1), [&](const tbb::blocked_range<int>& range) {
    for (int tile = range.begin(); tile < range.end(); ++tile) {
      SampleContext& ctx = contexts_[size_t(tile)];
      ctx.counter = RayCounter{};
      ctx.splats.clear();
      ctx.strategies.clear();
      ctx.recordStrategies = recordStrategies_;
      ctx.recordSpectral = recordSpectral_;
      if (recordSpectral_) tileSpectral_[size_t(tile)].clear();
      ctx.pass = passData.get();
      forEachPixelOfTile(tile, [&](int x, int y, size_t pixel) {
        Vec3* out = rec.samples.data() + pixel * size_t(count);
        for (int s = first; s < first + count; ++s) {
          Sampler rng(sampler_, seedMix_, uint64_t(pixel), uint32_t(s));
          out[s - first] = integrator_.samplePixel(scene_, Vec2(float(x), float(y)), rng, ctx);
          if (recordSpectral_) {
            rec.spectralCounts[pixel * size_t(count) + size_t(s - first)] = uint32_t(ctx.spectral.size());
            std::vector<SpectralSample>& shares = tileSpectral_[size_t(tile)];
            shares.insert(shares.end(), ctx.spectral.begin(), ctx.spectral.end());
            ctx.spectral.clear();
          }
        }
      });
    }
  }, tbb::simple_partitioner());
  // Gathered in tile order, so the record does not depend on scheduling.
  for (const std::vector<SpectralSample>& shares : tileSpectral_) rec.spectral.insert(rec.spectral.end(), shares.begin(), shares.end());
  for (SampleContext& ctx : contexts_) {
    rec.rays.closest += ctx.counter.closest;
    rec.rays.shadow += ctx.counter.shadow;
    rec.splats.insert(rec.splats.end(), ctx.splats.begin(), ctx.splats.end());
    rec.strategies.insert(rec.strategies.end(), ctx.strategies.begin(), ctx.strategies.end());
  }
}

void PassTracer::commit(const PassRecord& rec, Film& film, SpectralFilm* spectral,
                        const std::function<void(const StrategySample&)>& strategies) const {
  const bool shares = spectral && !rec.spectralCounts.empty();
  size_t next = 0;  // the next spectral share, read in the order trace() wrote them
  for (int tile = 0; tile < tileCount_; ++tile)
    forEachPixelOfTile(tile, [&](int x, int y, size_t pixel) {
      const size_t base = pixel * size_t(rec.count);
      for (int i = 0; i < rec.count; ++i) {
        const Vec3& xyz = rec.samples[base + size_t(i)];
        film.add(x, y, xyz);
        if (!shares) continue;
        // A sample's shares go to the bins unless the film dropped its XYZ as non-finite.
        const size_t n = rec.spectralCounts[base + size_t(i)];
        if (isFinite(xyz))
          for (size_t k = next; k < next + n; ++k) spectral->add(x, y, rec.spectral[k].lambda, rec.spectral[k].value);
        next += n;
      }
    });
  for (const Splat& sp : rec.splats) {
    // A splat at a non-finite position is counted like a non-finite sample (pixel -1, -1), a
    // non-finite value once, at the pixel holding it.
    if (!std::isfinite(sp.pixel.x) || !std::isfinite(sp.pixel.y)) {
      film.addNonFinite(-1, -1);
      continue;
    }
    if (!isFinite(sp.xyz)) {
      PixelFilter().splat(sp.pixel, w_, h_, [&](int x, int y, float) { film.addNonFinite(x, y); });
      continue;
    }
    // To every pixel whose reconstruction filter reaches the splat (core/pixel_filter.h).
    scene_.pixelFilter.splat(sp.pixel, w_, h_, [&](int x, int y, float weight) {
      film.addSplat(x, y, sp.xyz * weight);
      if (spectral) spectral->add(x, y, sp.lambda, sp.value * weight);
    });
  }
  if (strategies)
    for (const StrategySample& r : rec.strategies) strategies(r);
}

}  // namespace kasha
