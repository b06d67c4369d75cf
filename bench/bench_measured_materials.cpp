// Micro-benchmarks of the measured fluorescent materials on the pink Post-it note: the measured
// reradiation matrix (bilinear, row/column mixture sampling) against its Zhdanov fit (factorised),
// sample() in both transport modes and eval() of the fluorescent lobe.
#include <benchmark/benchmark.h>

#include <memory>
#include <stdexcept>
#include <string>

#include "core/rng.h"
#include "scene/scene_loader.h"

namespace kasha {
namespace {

// The Bsdf of the first material of the given type in the Post-it scene (the pink note comes first).
Bsdf postIt(const std::string& type) {
  static const std::unique_ptr<Scene> scene = loadScene(std::string(KASHA_SOURCE_DIR) + "/scenes/postit_d65.json");
  for (const auto& m : scene->materials)
    if (m->describe() == type) return m->bsdf(HitContext{});
  throw std::runtime_error("no " + type + " material in postit_d65.json");
}
const std::string kMeasured = "measured_reradiation", kFit = "zhdanov";

void sampleMaterial(benchmark::State& state, const std::string& type, TransportMode mode) {
  const Bsdf m = postIt(type);
  const Vec3 wKnown = glm::normalize(Vec3(0.2f, 0.3f, 0.9f));
  Rng rng(11);
  for (auto _ : state) {
    const float lambda = 360.0f + 470.0f * rng.uniform();
    benchmark::DoNotOptimize(m.sample(mode, wKnown, lambda, Vec3(rng.uniform(), rng.uniform(), rng.uniform())));
  }
}
void BM_MeasuredSampleRadiance(benchmark::State& s) { sampleMaterial(s, kMeasured, TransportMode::Radiance); }
void BM_MeasuredSampleImportance(benchmark::State& s) { sampleMaterial(s, kMeasured, TransportMode::Importance); }
void BM_ZhdanovFitSampleRadiance(benchmark::State& s) { sampleMaterial(s, kFit, TransportMode::Radiance); }
void BM_ZhdanovFitSampleImportance(benchmark::State& s) { sampleMaterial(s, kFit, TransportMode::Importance); }
BENCHMARK(BM_MeasuredSampleRadiance);
BENCHMARK(BM_MeasuredSampleImportance);
BENCHMARK(BM_ZhdanovFitSampleRadiance);
BENCHMARK(BM_ZhdanovFitSampleImportance);

void evalFluorescent(benchmark::State& state, const std::string& type) {
  const Bsdf m = postIt(type);
  const Vec3 wi = glm::normalize(Vec3(0.2f, 0.3f, 0.9f)), wo = glm::normalize(Vec3(-0.4f, 0.1f, 0.8f));
  Rng rng(5);
  for (auto _ : state) {
    const float li = 360.0f + 300.0f * rng.uniform(), lo = li + 150.0f * rng.uniform();
    benchmark::DoNotOptimize(m.eval({TransportMode::Radiance, SpectralLobe::Fluorescent, li, lo}, wi, wo));
  }
}
void BM_MeasuredEvalFluorescent(benchmark::State& s) { evalFluorescent(s, kMeasured); }
void BM_ZhdanovFitEvalFluorescent(benchmark::State& s) { evalFluorescent(s, kFit); }
BENCHMARK(BM_MeasuredEvalFluorescent);
BENCHMARK(BM_ZhdanovFitEvalFluorescent);

}  // namespace
}  // namespace kasha

BENCHMARK_MAIN();
