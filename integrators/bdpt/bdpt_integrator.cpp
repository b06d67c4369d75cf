#include "integrators/bdpt/bdpt_integrator.h"

#include <atomic>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "core/color.h"
#include "integrators/bdpt/connect.h"
#include "integrators/bdpt/family_pilot.h"
#include "integrators/direct_emission.h"
#include "integrators/progressive_schedule.h"

namespace kasha {
namespace {

struct MollifyPass final : PassData {
  explicit MollifyPass(float h) : bandwidth(h) {}
  float bandwidth;
};

// The unified estimator's pass: whether its samples run the own family (the pilot's decision).
struct FamiliesPass final : PassData {
  explicit FamiliesPass(bool own) : keepOwn(own) {}
  bool keepOwn;
};

// The own family's cost per camera sample, relative to the shared family alone: bdpt's time per
// sample over bdpt-shared's in the convergence report (docs/bdpt-mis.md §13). The pilot keeps the
// own family where the shared family alone has a relative variance per sample above this factor
// times both families'.
constexpr double kOwnFamilyCost = 1.15;

}  // namespace

Bdpt::Bdpt(const Scene& scene, const RenderSettings& s, bdpt::WavelengthMode mode, const MollificationSettings* m)
    : sensor_(s.wavelengths.sensor, WavelengthSources(scene), WavelengthSite::Sensor),
      light_(s.wavelengths.light, WavelengthSources(scene), WavelengthSite::LightStart),
      ws_{s.maxDepth, s.rrDepth, &light_.density(), nullptr, {}}, mode_(mode), families_(bdpt::familiesFor(scene, mode)),
      directXyz_(directEmissionXyz(scene)) {
  requireDensity(s.wavelengths.sensor, WavelengthSite::Sensor, "by bdpt (its MIS weights need the sensor's density)");
  requireDensity(s.wavelengths.light, WavelengthSite::LightStart, "by bdpt (its MIS weights need the light-start density)");
  // Wavelength lanes (docs/bdpt-mis.md §10), in every family.
  // The unified estimator carries both families on one light subpath (docs/bdpt-mis.md §11).
  if (mode_ == bdpt::WavelengthMode::Unified && families_.independent) {
    lightFirst_ = std::make_unique<bdpt::LightFirstStart>(scene, s.wavelengths.light);
    ws_.lightFirst = lightFirst_.get();
    wsShared_ = ws_;
    wsShared_.lightFirst = nullptr;
    familyChoice_ = s.bdptFamilies;
  }
  lanes_ = s.heroWavelengths == kAutoLanes ? kDefaultLanes : s.heroWavelengths;
  if (lanes_ < 1 || lanes_ > kMaxLanes)
    throw std::invalid_argument("bdpt: hero wavelengths " + std::to_string(lanes_) + " is outside [1, " +
                                std::to_string(kMaxLanes) + "]");
  if (!m) return;
  if (mode_ != bdpt::WavelengthMode::Independent)
    throw std::invalid_argument("bdpt: mollification needs the independent wavelength family");
  if (!(m->bandwidth >= 0.0f)) throw std::invalid_argument("bdpt: the mollification bandwidth must not be negative");
  if (!(m->alpha > 0.0f && m->alpha < 1.0f)) throw std::invalid_argument("bdpt: the mollification alpha must be in (0, 1)");
  bandwidth1_ = m->bandwidth > 0.0f ? m->bandwidth : 0.02f * (scene.range.max - scene.range.min);
  alpha_ = m->alpha;
}

std::string Bdpt::name() const {
  if (mollifies()) return "bdpt-mollified";
  if (mode_ == bdpt::WavelengthMode::Unified) return "bdpt";
  return mode_ == bdpt::WavelengthMode::Shared ? "bdpt-shared" : "bdpt-independent";
}

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
    const bool own = keepsOwnFamily(scene, seed, pilotRays);
    if (firstSample == 0) counter.closest += pilotRays.closest, counter.shadow += pilotRays.shadow;
    return std::make_unique<FamiliesPass>(own);
  }
  return nullptr;
}

bool Bdpt::sharedAlone(const PassData* pass) const {
  if (!lightFirst_) return false;
  if (familyChoice_ == BdptFamilies::Shared) return true;
  return familyChoice_ == BdptFamilies::Auto && pass && !static_cast<const FamiliesPass&>(*pass).keepOwn;
}

bool Bdpt::keepsOwnFamily(const Scene& scene, uint64_t seed, RayCounter& counter) const {
  std::lock_guard<std::mutex> lock(pilotMutex_);
  if (pilot_ && pilot_->seed == seed) return pilot_->keepOwn;
  using namespace bdpt;
  std::atomic<uint64_t> unshared{0};
  // Both families, and from their paths what the shared family alone would add (PilotMoments).
  const PilotSample both = [&](Vec2 pixel, Sampler& rng, SampleContext& ctx, std::vector<Splat>& excess) -> Vec3 {
    thread_local PilotMoments moments;
    moments.unshared = 0;
    moments.excess.clear();
    const Vec3 v = estimate(scene, pixel, rng, ctx, false, &moments);
    if (moments.unshared > 0) unshared.fetch_add(uint64_t(moments.unshared), std::memory_order_relaxed);
    excess.insert(excess.end(), moments.excess.begin(), moments.excess.end());
    return v;
  };
  const PilotEstimates e = pilotEstimates(scene.camera.width(), scene.camera.height(), seed, SamplerKind::Independent, both);
  counter = e.rays;
  // Where the shared family alone cannot sample a path that carries light, it would miss that light
  // (bdpt-shared's bias: a delta light seen through a specular vertex exciting fluorescence).
  // Otherwise it runs alone where its relative variance per sample, estimated from both families'
  // paths, is at most kOwnFamilyCost times theirs.
  PilotOutcome o;
  o.seed = seed;
  o.unshared = unshared.load() > 0;
  o.relVarBoth = e.relVar;
  o.relVarSharedAlone = e.relVar + e.relExcess;
  o.keepOwn = o.unshared || o.relVarSharedAlone > kOwnFamilyCost * o.relVarBoth;
  pilot_ = o;
  return o.keepOwn;
}

std::string Bdpt::choices() const {
  if (!lightFirst_ || familyChoice_ == BdptFamilies::Both) return {};
  if (familyChoice_ == BdptFamilies::Shared) return "families: shared";
  std::lock_guard<std::mutex> lock(pilotMutex_);
  if (!pilot_) return {};
  char buf[300];
  std::snprintf(buf, sizeof buf, "families: %s (pilot: relative variance per sample %.3g with both, %.3g shared alone%s)",
                pilot_->keepOwn ? "both" : "shared", pilot_->relVarBoth, pilot_->relVarSharedAlone,
                pilot_->unshared ? ", which cannot sample some paths that carry light" : "");
  return buf;
}

int Bdpt::maxSamplesPerPass() const { return mollifies() ? 1 : Integrator::maxSamplesPerPass(); }

Vec3 Bdpt::samplePixel(const Scene& scene, Vec2 pixel, Sampler& rng, SampleContext& ctx) const {
  return estimate(scene, pixel, rng, ctx, sharedAlone(ctx.pass), nullptr);
}

Vec3 Bdpt::estimate(const Scene& scene, Vec2 pixel, Sampler& rng, SampleContext& ctx, bool alone,
                    bdpt::PilotMoments* pilot) const {
  using namespace bdpt;
  // The camera subpath, the shared and own light subpaths.
  thread_local std::vector<PathVertex> C, LS, LO;
  if (C.capacity() < 16) C.reserve(16), LS.reserve(16), LO.reserve(16);
  thread_local LaneTables laneTables;
  const WalkSettings& ws = alone ? wsShared_ : ws_;
  const Families families = alone ? Families{true, false} : families_;
  const Lanes lanes = sensorLanes(scene, sensor_.density(), rng.uniform(), lanes_, laneTables,
                                  families.independent && !ws.lightFirst ? &light_.density() : nullptr, ws.lightFirst);
  for (int k = 0; k < lanes_; ++k)
    if (lanes.sensorPdf[k] <= 0.0f) return Vec3(0.0f);
  traceCameraSubpath(scene, pixel + rng.uniform2(), lanes, ws, rng, ctx.counter, C);
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
  c.pilot = pilot;
  c.pixel = pixel;
  c.spectralSplats = ctx.recordSpectral;
  if (lanes_ > 1 && !ctx.recordSpectral) c.directXyz = &directXyz_;
  if (mollifies()) c.bandwidth = static_cast<const MollifyPass&>(*ctx.pass).bandwidth;
  if (ctx.recordStrategies) c.log = &ctx.strategies;

  float radiance[kMaxLanes];
  Vec3 xyz;
  connectSubpaths(c, C, LS, LO, rng, ctx.splats, radiance, xyz);
  // Each lane's radiance weighted by W(λ_k)/(n·p(λ_k)): the balance heuristic over the n stratified
  // hero techniques (every lane distributed as p).
  for (int k = 0; k < lanes_; ++k)
    xyz += sensorResponse(ctx, lanes.lambda[k], lanes.response[k], radiance[k] / (float(lanes_) * lanes.sensorPdf[k]));
  return xyz;
}

}  // namespace kasha
