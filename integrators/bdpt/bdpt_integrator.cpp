#include "integrators/bdpt/bdpt_integrator.h"

#include <cmath>
#include <stdexcept>

#include "core/color.h"
#include "integrators/bdpt/connect.h"
#include "integrators/direct_emission.h"
#include "integrators/progressive_schedule.h"

namespace kasha {
namespace {

struct MollifyPass final : PassData {
  explicit MollifyPass(float h) : bandwidth(h) {}
  float bandwidth;
};

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

std::unique_ptr<const PassData> Bdpt::beginPass(const Scene&, int firstSample, int, uint64_t, RayCounter&) const {
  if (!mollifies()) return nullptr;
  return std::make_unique<MollifyPass>(bandwidth(firstSample));
}

int Bdpt::maxSamplesPerPass() const { return mollifies() ? 1 : Integrator::maxSamplesPerPass(); }

Vec3 Bdpt::samplePixel(const Scene& scene, Vec2 pixel, Sampler& rng, SampleContext& ctx) const {
  using namespace bdpt;
  thread_local std::vector<PathVertex> C, LS, LO;  // the camera subpath, the shared and own light subpaths
  if (C.capacity() < 16) C.reserve(16), LS.reserve(16), LO.reserve(16);
  thread_local LaneTables laneTables;
  const Lanes lanes = sensorLanes(scene, sensor_.density(), rng.uniform(), lanes_, laneTables,
                                  families_.independent && !lightFirst_ ? &light_.density() : nullptr, lightFirst_.get());
  for (int k = 0; k < lanes_; ++k)
    if (lanes.sensorPdf[k] <= 0.0f) return Vec3(0.0f);
  const Vec2 film = pixel + rng.uniform2();
  traceCameraSubpath(scene, film, lanes, ws_, rng, ctx.counter, C);
  LS.clear(), LO.clear();
  int sharedLightVertices = 0;
  if (lightFirst_) {
    sharedLightVertices = traceMergedLightSubpath(scene, lanes, ws_, rng, ctx.counter, LS, LO);
  } else {
    if (families_.shared) traceLightSubpath(scene, LightFamily::Shared, lanes, ws_, rng, ctx.counter, LS);
    if (families_.independent) traceLightSubpath(scene, LightFamily::Own, lanes, ws_, rng, ctx.counter, LO);
  }
  Context c{scene, ws_, families_, lanes, sensor_.density(), ctx.counter};
  c.sharedLightVertices = sharedLightVertices;
  c.spectralSplats = ctx.recordSpectral;
  if (lanes_ > 1 && !ctx.recordSpectral) c.directXyz = &directXyz_;
  if (mollifies()) c.bandwidth = static_cast<const MollifyPass&>(*ctx.pass).bandwidth;
  if (ctx.recordStrategies) {
    c.log = &ctx.strategies;
    c.pixel = pixel;
  }

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
