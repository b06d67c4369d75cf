#include "integrators/bdpt/bdpt_integrator.h"

#include <cmath>
#include <stdexcept>

#include "core/color.h"
#include "integrators/bdpt/connect.h"
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
      ws_{s.maxDepth, s.rrDepth, mode, &light_.density()} {
  requireDensity(s.wavelengths.sensor, WavelengthSite::Sensor, "by bdpt (its MIS weights need the sensor's density)");
  requireDensity(s.wavelengths.light, WavelengthSite::LightStart, "by bdpt (its MIS weights need the light-start density)");
  if (!m) return;
  if (ws_.mode != bdpt::WavelengthMode::Independent)
    throw std::invalid_argument("bdpt: mollification needs the independent wavelength family");
  if (!(m->bandwidth >= 0.0f)) throw std::invalid_argument("bdpt: the mollification bandwidth must not be negative");
  if (!(m->alpha > 0.0f && m->alpha < 1.0f)) throw std::invalid_argument("bdpt: the mollification alpha must be in (0, 1)");
  bandwidth1_ = m->bandwidth > 0.0f ? m->bandwidth : 0.02f * (scene.range.max - scene.range.min);
  alpha_ = m->alpha;
}

std::string Bdpt::name() const {
  if (mollifies()) return "bdpt-mollified";
  return ws_.mode == bdpt::WavelengthMode::Shared ? "bdpt-shared" : "bdpt-independent";
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
  thread_local std::vector<PathVertex> C, L;
  if (C.capacity() < 16) C.reserve(16), L.reserve(16);
  const WavelengthSample ws = sensor_.density().sample(rng.uniform());
  if (ws.pdf <= 0.0f) return Vec3(0.0f);
  const Vec2 film = pixel + rng.uniform2();
  traceCameraSubpath(scene, film, ws.lambda, ws.pdf, ws_, rng, ctx.counter, C);
  traceLightSubpath(scene, ws.lambda, ws_, rng, ctx.counter, L);
  Context c{scene, ws_, ws.lambda, ws.pdf, sensor_.density(), ctx.counter};
  if (mollifies()) c.bandwidth = static_cast<const MollifyPass&>(*ctx.pass).bandwidth;
  const Vec3 pixelScale = Observer::cie1931().weight(ws.lambda) / ws.pdf;  // W(λ)/p(λ)
  if (ctx.recordStrategies) {
    c.log = &ctx.strategies;
    c.pixel = pixel;
    c.pixelScale = pixelScale;
  }

  // Strategies with t ≥ 2 estimate this pixel's radiance at the sensor's wavelength.
  float L_pixel = 0.0f;
  for (int t = 2; t <= int(C.size()); ++t) {
    const PathVertex& ct = C[size_t(t - 1)];
    L_pixel += emitterHit(c, C, t);
    if (ct.kind != PathVertex::Kind::Surface) continue;
    if (t - 1 <= ws_.maxDepth) {
      L_pixel += nextEvent(c, C, t, rng);
      if (ws_.mode == WavelengthMode::Independent && !L.empty()) L_pixel += connectLightVertex(c, L, C, t);
    }
    for (int s = 2; s <= int(L.size()) && (s - 1) + (t - 1) <= ws_.maxDepth; ++s) L_pixel += connect(c, L, s, C, t);
  }
  // t = 1: light subpath vertices seen by the pinhole, splatted to their pixels.
  for (int s = 1; s <= int(L.size()) && s - 1 <= ws_.maxDepth; ++s) connectToCamera(c, L, s, ctx.splats);
  return sensorResponse(ctx, ws.lambda, L_pixel / ws.pdf);
}

}  // namespace kasha
