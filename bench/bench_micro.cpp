// Micro-benchmarks of the inner-loop operations: spectrum lookups, wavelength sampling, the Jung18
// BBRRDF and the Lambertian, and Embree ray queries into the default Cornell scene.
#include <benchmark/benchmark.h>

#include <cmath>
#include <memory>
#include <optional>
#include <vector>

#include "core/rng.h"
#include "scene/scene_loader.h"
#include "core/spectral_distribution.h"
#include "core/spectrum.h"
#include "materials/jung_bbrrdf.h"
#include "materials/lambertian.h"

namespace kasha {
namespace {

const WavelengthRange kRange{360.0f, 830.0f};

// A smooth table with equally spaced knots over the range (as measured data usually is).
Spectrum table(float stepNm) {
  std::vector<float> x, y;
  for (float l = kRange.min; l <= kRange.max; l += stepNm) {
    x.push_back(l);
    y.push_back(0.5f + 0.4f * std::sin(0.02f * l));
  }
  return Spectrum::piecewiseLinear(std::move(x), std::move(y));
}

// Random wavelengths drawn outside the timed loop, so the timing is of the lookup alone.
std::vector<float> randomLambdas(size_t n) {
  Rng rng(42);
  std::vector<float> v(n);
  for (float& l : v) l = kRange.min + rng.uniform() * kRange.width();
  return v;
}

void lookup(benchmark::State& state, float stepNm) {
  const Spectrum s = table(stepNm);
  const std::vector<float> ls = randomLambdas(4096);
  size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(s(ls[i]));
    i = (i + 1) & 4095;
  }
}
void BM_SpectrumLookup1nm(benchmark::State& state) { lookup(state, 1.0f); }
void BM_SpectrumLookup4nm(benchmark::State& state) { lookup(state, 4.0f); }
BENCHMARK(BM_SpectrumLookup1nm);
BENCHMARK(BM_SpectrumLookup4nm);

// Non-uniform knots (a step in a box): the binary-search path.
void BM_SpectrumLookupBox(benchmark::State& state) {
  const Spectrum s = Spectrum::box(400.0f, 450.0f, 0.8f);
  const std::vector<float> ls = randomLambdas(4096);
  size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(s(ls[i]));
    i = (i + 1) & 4095;
  }
}
BENCHMARK(BM_SpectrumLookupBox);

void BM_SpectralDistributionSample(benchmark::State& state) {
  const SpectralDistribution d(table(1.0f), kRange);
  Rng rng(1);
  for (auto _ : state) benchmark::DoNotOptimize(d.sample(rng.uniform()));
}
BENCHMARK(BM_SpectralDistributionSample);

JungParams gaussianParams() {
  JungParams p;
  p.absorption = Spectrum::gaussian(490.0f, 40.0f, 0.9f);
  p.emission = Spectrum::gaussian(530.0f, 50.0f);
  p.reflectance = table(4.0f);
  p.concentration = 0.8f;
  p.energyRatio = 0.9f;
  return p;
}

void BM_JungEval(benchmark::State& state) {
  const JungBbrrdf m(gaussianParams(), kRange);
  const std::vector<float> ls = randomLambdas(4096);
  const Vec3 wi = glm::normalize(Vec3(0.2f, 0.3f, 0.9f)), wo = glm::normalize(Vec3(-0.5f, 0.1f, 0.6f));
  size_t i = 0;
  for (auto _ : state) {
    const float l1 = ls[i], l2 = ls[(i + 1) & 4095];
    benchmark::DoNotOptimize(m.eval({TransportMode::Radiance, SpectralLobe::Elastic, l1, l1}, wi, wo));
    benchmark::DoNotOptimize(m.eval({TransportMode::Radiance, SpectralLobe::Fluorescent, l1, l2}, wi, wo));
    i = (i + 1) & 4095;
  }
  state.SetLabel("elastic + fluorescent");
}
BENCHMARK(BM_JungEval);

void jungSample(benchmark::State& state, TransportMode mode) {
  const JungBbrrdf m(gaussianParams(), kRange);
  const std::vector<float> ls = randomLambdas(4096);
  const Vec3 wKnown = glm::normalize(Vec3(0.2f, 0.3f, 0.9f));
  Rng rng(7);
  size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(m.sample(mode, wKnown, ls[i], Vec3(rng.uniform(), rng.uniform(), rng.uniform())));
    i = (i + 1) & 4095;
  }
}
void BM_JungSampleRadiance(benchmark::State& state) { jungSample(state, TransportMode::Radiance); }
void BM_JungSampleImportance(benchmark::State& state) { jungSample(state, TransportMode::Importance); }
BENCHMARK(BM_JungSampleRadiance);
BENCHMARK(BM_JungSampleImportance);

void BM_LambertianSample(benchmark::State& state) {
  const Lambertian m(table(4.0f));
  const std::vector<float> ls = randomLambdas(4096);
  const Vec3 wKnown = glm::normalize(Vec3(0.2f, 0.3f, 0.9f));
  Rng rng(8);
  size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(
        m.sample(TransportMode::Radiance, wKnown, ls[i], Vec3(rng.uniform(), rng.uniform(), rng.uniform())));
    i = (i + 1) & 4095;
  }
}
BENCHMARK(BM_LambertianSample);

// ---- Embree queries into the default Cornell scene, camera rays through random pixels.

const Scene& cornell() {
  static const std::unique_ptr<Scene> scene = loadScene(KASHA_SOURCE_DIR "/scenes/cornell_fluorescent.json");
  return *scene;
}

std::vector<Ray> cameraRays(const Scene& s, size_t n) {
  Rng rng(5);
  std::vector<Ray> rays(n);
  for (Ray& r : rays)
    r = s.camera.generateRay(Vec2(rng.uniform() * float(s.camera.width()), rng.uniform() * float(s.camera.height())),
                             Vec2(rng.uniform(), rng.uniform()));
  return rays;
}

void BM_EmbreeClosestHit(benchmark::State& state) {
  const Scene& s = cornell();
  const std::vector<Ray> rays = cameraRays(s, 4096);
  size_t i = 0, hits = 0;
  for (auto _ : state) {
    const std::optional<Hit> h = s.accel->intersect(rays[i]);
    hits += h.has_value();
    benchmark::DoNotOptimize(h);
    i = (i + 1) & 4095;
  }
  state.counters["hit_fraction"] = double(hits) / double(state.iterations());
}
BENCHMARK(BM_EmbreeClosestHit);

void BM_EmbreeOcclusion(benchmark::State& state) {
  const Scene& s = cornell();
  const std::vector<Ray> rays = cameraRays(s, 4096);
  size_t i = 0, blocked = 0;
  for (auto _ : state) {
    const bool o = s.accel->occluded(rays[i].o, rays[i].d, 5000.0f);
    blocked += o;
    benchmark::DoNotOptimize(o);
    i = (i + 1) & 4095;
  }
  state.counters["occluded_fraction"] = double(blocked) / double(state.iterations());
}
BENCHMARK(BM_EmbreeOcclusion);

}  // namespace
}  // namespace kasha

BENCHMARK_MAIN();
