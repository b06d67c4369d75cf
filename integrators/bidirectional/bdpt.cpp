#include "integrators/bidirectional/bdpt.h"

#include <atomic>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "core/color.h"
#include "integrators/bidirectional/connect.h"
#include "integrators/bidirectional/family_pilot.h"
#include "integrators/bidirectional/path_media.h"
#include "integrators/bidirectional/pilot_observer.h"
#include "integrators/bidirectional/strategy_images.h"
#include "integrators/direct_emission.h"
#include "integrators/progressive_schedule.h"

namespace kasha {
namespace {

struct MollifyPass final : PassData {
  explicit MollifyPass(float h) : bandwidth(h) {}
  float bandwidth;
};

// The unified estimator's pass: the families its samples run (the pilot's decision).
struct FamiliesPass final : PassData {
  explicit FamiliesPass(BdptFamilies r) : run(r) {}
  BdptFamilies run;
};

// The pilot's cost model (docs/bdpt-mis.md §13): time per sample ∝ rays per sample, times this factor
// where the own family runs (its per-lane weights): the time per ray of bdpt with both families,
// and of bdpt-independent, over bdpt-shared's, 1.13–1.26 (mean 1.19) and 1.04–1.24 (mean 1.16) on
// the convergence report's six scenes (1 thread, 32 spp).
constexpr double kOwnFamilyCostPerRay = 1.19;

}  // namespace

namespace {

// The families' choice as a wavelength mode: one family alone, or both in one MIS (the pilot may
// still run one alone per render).
bidir::WavelengthMode modeOf(BdptFamilies families) {
  if (families == BdptFamilies::Shared) return bidir::WavelengthMode::Shared;
  if (families == BdptFamilies::Own) return bidir::WavelengthMode::Independent;
  return bidir::WavelengthMode::Unified;
}

}  // namespace

Bdpt::Bdpt(const Scene& scene, const RenderSettings& s)
    : sensor_(s.wavelengths.sensor, WavelengthSources(scene), WavelengthSite::Sensor),
      light_(s.wavelengths.light, WavelengthSources(scene), WavelengthSite::LightStart),
      ws_{s.maxDepth, s.rrDepth, &light_.density(), nullptr, {}, s.hideEmitters}, mode_(modeOf(s.bdpt.families)),
      families_(bidir::familiesFor(scene, mode_)), directXyz_(directEmissionXyz(scene)) {
  requireDensity(s.wavelengths.sensor, WavelengthSite::Sensor, "by bdpt (its MIS weights need the sensor's density)");
  requireDensity(s.wavelengths.light, WavelengthSite::LightStart, "by bdpt (its MIS weights need the light-start density)");
  checkBdptSettings(s.bdpt, [](const char* key, const std::string& why) {
    throw std::invalid_argument(std::string("bdpt: render/bdpt/") + key + " " + why);
  });
  // In scenes with media (docs/media.md §5) every free flight's density depends on the wavelength:
  // the lanes end at a flight through a medium, and the families trace light subpaths of their own.
  const bool media = scene.hasMedia();
  if (media) bidir::requireBidirectionalMedia(s, name());
  // Wavelength lanes (docs/bdpt-mis.md §10), in every family.
  // The unified estimator carries both families on one light subpath (docs/bdpt-mis.md §11).
  if (mode_ == bidir::WavelengthMode::Unified && families_.independent && !media) {
    lightFirst_ = std::make_unique<bidir::LightFirstStart>(scene, s.wavelengths.light);
    ws_.lightFirst = lightFirst_.get();
    wsAlone_ = ws_;
    wsAlone_.lightFirst = nullptr;
    familyChoice_ = s.bdpt.families;
  }
  lanes_ = s.heroWavelengths == kAutoLanes ? kDefaultLanes : s.heroWavelengths;
  if (lanes_ < 1 || lanes_ > kMaxLanes)
    throw std::invalid_argument("bdpt: hero wavelengths " + std::to_string(lanes_) + " is outside [1, " +
                                std::to_string(kMaxLanes) + "]");
  if (!s.bdpt.mollify) return;
  bandwidth1_ = s.bdpt.mollifyBandwidth > 0.0f ? s.bdpt.mollifyBandwidth : 0.02f * (scene.range.max - scene.range.min);
  alpha_ = s.bdpt.mollifyAlpha;
}

std::string Bdpt::name() const { return "bdpt"; }

float Bdpt::bandwidth(int sample) const {
  return bandwidth1_ * std::sqrt(progressiveRadiusSquared(1.0f, alpha_, sample + 1));
}

std::unique_ptr<const PassData> Bdpt::beginPass(const Scene& scene, int firstSample, int, uint64_t seed,
                                                RayCounter& counter) const {
  if (mollifies()) return std::make_unique<MollifyPass>(bandwidth(firstSample));
  if (lightFirst_ && familyChoice_ == BdptFamilies::Auto) {
    // Every process runs the pilot once; its rays count in the pass that takes sample 0, so that the
    // statistics do not depend on the number of processes (render_group.h).
    RayCounter pilotRays;
    const BdptFamilies run = pilotChoice(scene, seed, pilotRays);
    if (firstSample == 0) counter.closest += pilotRays.closest, counter.shadow += pilotRays.shadow;
    return std::make_unique<FamiliesPass>(run);
  }
  return nullptr;
}

BdptFamilies Bdpt::familiesOf(const PassData* pass) const {
  if (!lightFirst_) return BdptFamilies::Both;  // the mode's families
  if (familyChoice_ == BdptFamilies::Auto) return pass ? static_cast<const FamiliesPass&>(*pass).run : BdptFamilies::Both;
  return familyChoice_;
}

BdptFamilies Bdpt::pilotChoice(const Scene& scene, uint64_t seed, RayCounter& counter) const {
  std::lock_guard<std::mutex> lock(pilotMutex_);
  if (pilot_ && pilot_->seed == seed) return pilot_->run;
  using namespace bidir;
  constexpr int kFamilies = 2;  // the alternatives weighed here: Alone::Shared and Alone::Own
  std::atomic<uint64_t> unsampled[kFamilies] = {};
  // Both families, and from their paths what each family alone would add (PilotMoments).
  const PilotSample both = [&](Vec2 pixel, Sampler& rng, SampleContext& ctx,
                               std::vector<std::vector<Splat>>& excess) -> Vec3 {
    thread_local PilotMoments moments;
    moments.clear();
    PilotObserver observer(moments);
    const Vec3 v = estimate(scene, pixel, rng, ctx, BdptFamilies::Both, &observer);
    for (int a = 0; a < kFamilies; ++a) {
      const PilotMoments::Alternative& alt = moments.alone[a];
      if (alt.unsampled > 0) unsampled[a].fetch_add(uint64_t(alt.unsampled), std::memory_order_relaxed);
      excess[size_t(a)].insert(excess[size_t(a)].end(), alt.excess.begin(), alt.excess.end());
    }
    return v;
  };
  const int w = scene.camera.width(), h = scene.camera.height();
  const PilotEstimates e = pilotEstimates(w, h, seed, SamplerKind::Independent, kFamilies, both);
  counter = e.rays;
  // Each family alone's rays per sample, from samples of its own (their rays count with the pilot's).
  const auto raysAlone = [&](BdptFamilies run) {
    const PilotSample alone = [&](Vec2 pixel, Sampler& rng, SampleContext& ctx, std::vector<std::vector<Splat>>&) {
      return estimate(scene, pixel, rng, ctx, run, nullptr);
    };
    return raysPerSample(w, h, seed, alone, counter);
  };
  PilotOutcome o;
  o.seed = seed;
  o.both.relVar = e.relVar;
  o.both.rays = double(e.rays.closest + e.rays.shadow) / double(e.samples);
  o.both.cost = o.both.rays * kOwnFamilyCostPerRay;
  // A family alone that cannot sample a path carrying light would miss that light (bdpt-shared's
  // bias: a delta light seen through a specular vertex exciting fluorescence).
  o.shared.samplesAll = unsampled[int(Alone::Shared)].load() == 0;
  o.shared.relVar = e.relVar + e.relExcess[size_t(Alone::Shared)];
  o.shared.rays = raysAlone(BdptFamilies::Shared);
  o.shared.cost = o.shared.rays;
  o.own.samplesAll = unsampled[int(Alone::Own)].load() == 0;
  o.own.relVar = e.relVar + e.relExcess[size_t(Alone::Own)];
  o.own.rays = raysAlone(BdptFamilies::Own);
  o.own.cost = o.own.rays * kOwnFamilyCostPerRay;
  // The most efficient (relative variance × cost per sample) of those that sample everything.
  double best = o.both.relVar * o.both.cost;
  if (o.shared.samplesAll && o.shared.relVar * o.shared.cost < best)
    o.run = BdptFamilies::Shared, best = o.shared.relVar * o.shared.cost;
  if (o.own.samplesAll && o.own.relVar * o.own.cost < best) o.run = BdptFamilies::Own;
  pilot_ = o;
  return o.run;
}

std::string Bdpt::choices() const {
  if (mode_ == bidir::WavelengthMode::Shared) return "families: shared";
  if (mode_ == bidir::WavelengthMode::Independent) return "families: own";
  if (!lightFirst_ || familyChoice_ == BdptFamilies::Both) return {};
  std::lock_guard<std::mutex> lock(pilotMutex_);
  if (!pilot_) return {};
  const auto alone = [](const PilotOutcome::Candidate& c) {
    char buf[120];
    if (!c.samplesAll) return std::string("cannot sample some paths that carry light");
    std::snprintf(buf, sizeof buf, "%.3g, %.3g rays", c.relVar, c.rays);
    return std::string(buf);
  };
  char buf[400];
  std::snprintf(buf, sizeof buf,
                "families: %s (pilot: relative variance per sample and rays per sample: both %.3g, %.3g rays; "
                "shared alone %s; own alone %s)",
                toString(pilot_->run), pilot_->both.relVar, pilot_->both.rays, alone(pilot_->shared).c_str(),
                alone(pilot_->own).c_str());
  return buf;
}

int Bdpt::maxSamplesPerPass() const { return mollifies() ? 1 : Integrator::maxSamplesPerPass(); }

Vec3 Bdpt::samplePixel(const Scene& scene, Vec2 pixel, Sampler& rng, SampleContext& ctx) const {
  return estimate(scene, pixel, rng, ctx, familiesOf(ctx.pass), nullptr);
}

Vec3 Bdpt::estimate(const Scene& scene, Vec2 pixel, Sampler& rng, SampleContext& ctx, BdptFamilies run,
                    bidir::MisObserver* observer) const {
  using namespace bidir;
  // The camera subpath, the shared and own light subpaths.
  thread_local std::vector<PathVertex> C, LS, LO;
  if (C.capacity() < 16) C.reserve(16), LS.reserve(16), LO.reserve(16);
  thread_local LaneTables laneTables;
  const bool alone = lightFirst_ && run != BdptFamilies::Both;
  const WalkSettings& ws = alone ? wsAlone_ : ws_;
  const Families families = !alone ? families_ : Families{run == BdptFamilies::Shared, run == BdptFamilies::Own};
  const Lanes lanes = sensorLanes(scene, sensor_.density(), rng.uniform(), lanes_, laneTables,
                                  families.independent ? &light_.density() : nullptr, ws.lightFirst);
  for (int k = 0; k < lanes_; ++k)
    if (lanes.pdf[k] <= 0.0f) return Vec3(0.0f);
  traceCameraSubpath(scene, scene.pixelFilter.filmPosition(pixel, rng.uniform2()), lanes, ws, rng, ctx.counter, C);
  LS.clear(), LO.clear();
  int sharedLightVertices = 0;
  if (ws.lightFirst) {
    sharedLightVertices = traceMergedLightSubpath(scene, lanes, ws, rng, ctx.counter, LS, LO);
  } else {
    if (families.shared) traceLightSubpath(scene, LightFamily::Shared, lanes, ws, rng, ctx.counter, LS);
    if (families.independent) traceLightSubpath(scene, LightFamily::Own, lanes, ws, rng, ctx.counter, LO);
  }
  Context c{scene, ws, families, lanes, sensor_.density(), ctx.counter};
  c.sharedLightVertices = sharedLightVertices;
  c.pixel = pixel;
  c.spectralSplats = ctx.recordSpectral;
  if (lanes_ > 1 && !ctx.recordSpectral && !scene.hasMedia()) c.directXyz = &directXyz_;
  if (mollifies()) c.bandwidth = static_cast<const MollifyPass&>(*ctx.pass).bandwidth;
  // The pilot's samples do not record strategies (pilotEstimates).
  StrategyLog log(ctx.strategies);
  c.observer = ctx.recordStrategies ? &log : observer;

  float radiance[kMaxLanes];
  Vec3 xyz;
  connectSubpaths(c, C, LS, LO, rng, ctx.splats, radiance, xyz);
  // Each lane's radiance weighted by W(λ_k)/(n·p(λ_k)): the balance heuristic over the n stratified
  // hero techniques (every lane distributed as p).
  for (int k = 0; k < lanes_; ++k)
    xyz += sensorResponse(ctx, lanes.lambda[k], lanes.response[k], radiance[k] / (float(lanes_) * lanes.pdf[k]));
  return xyz;
}

}  // namespace kasha
