#include "integrators/light_tracing/light_tracer.h"

#include <algorithm>

#include "core/color.h"
#include "integrators/light_subpath_lanes.h"

namespace kasha {
namespace {

// The film divides by samples per pixel, and there are w·h light subpaths per sample per pixel.
float perPath(const Scene& scene) { return 1.0f / (float(scene.camera.width()) * float(scene.camera.height())); }

bool visible(const Scene& scene, const Vec3& p, const Vec3& n, const Camera::Connection& c, SampleContext& ctx) {
  ++ctx.counter.shadow;
  const Vec3 origin = glm::dot(n, n) > 0.0f ? offsetPoint(p, n, c.wi) : p;
  return !scene.accel->occluded(origin, c.wi, c.dist * (1.0f - 1e-4f) - rayEpsilon(p));
}

// The XYZ of lane k's value[k] at lambda[k] (the sensor responds with W(λ_k)), summed over the lanes.
Vec3 lanesXyz(const float* lambda, const float* value, int n) {
  Vec3 xyz(0.0f);
  for (int k = 0; k < n; ++k) xyz += Observer::cie1931().weight(lambda[k]) * value[k];
  return xyz;
}

// Whether the lanes add anything the film keeps: XYZ, and with spectral bins any lane's value.
bool contributes(const SampleContext& ctx, const float* lambda, const float* value, int n) {
  if (ctx.recordSpectral) return std::any_of(value, value + n, [](float v) { return v != 0.0f; });
  return lanesXyz(lambda, value, n) != Vec3(0.0f);
}

// Splats the lanes' values, each times `scale`: as one XYZ splat, or with spectral bins one splat
// per lane, so that each bin gets its lane's share.
void splatLanes(SampleContext& ctx, Vec2 pixel, const float* lambda, const float* value, int n, float scale) {
  if (!ctx.recordSpectral) {
    ctx.splats.push_back({pixel, lanesXyz(lambda, value, n) * scale});
    return;
  }
  for (int k = 0; k < n; ++k)
    if (value[k] != 0.0f) ctx.splats.push_back(spectralSplat(pixel, lambda[k], value[k] * scale));
}


}  // namespace

LightTracer::LightTracer(const Scene& scene, const RenderSettings& s)
    : wavelengths_(s.wavelengths.light, WavelengthSources(scene), WavelengthSite::LightStart),
      lanes_(s.heroWavelengths),
      atFluorescence_(s.fluorescentLanes),
      maxDepth_(s.maxDepth),
      rrDepth_(s.rrDepth),
      hideEmitters_(s.hideEmitters) {
  requireDensity(s.wavelengths.light, WavelengthSite::LightStart, "for light subpaths");
  if (lanes_ < 1 || lanes_ > kMaxLanes)
    throw std::invalid_argument("wavelength lanes: " + std::to_string(lanes_) + " is outside [1, " +
                                std::to_string(kMaxLanes) + "]");
}

Vec3 LightTracer::samplePixel(const Scene& scene, Vec2, Sampler& rng, SampleContext& ctx) const {
  const int n = lanes_;
  // Lanes at the strata of the light-start density; the light ∝ Σ_j Φ_l(λ_j), symmetric in them.
  const float uLambda = rng.uniform(), uLight = rng.uniform();
  const Vec2 uPos = rng.uniform2(), uDir = rng.uniform2();
  const Vec2 uLens = scene.camera.sampleLens(rng);
  LightStartLanes st = startLightLanes(scene, wavelengths_.density(), n, uLambda, uLight, uPos, uDir);
  if (st.lanes.n == 0) return Vec3(0.0f);
  const EmissionSample& es = st.es;
  LightLanes& lanes = st.lanes;

  // The emitter seen directly (area lights; delta lights have no area the camera could see).
  if (!es.deltaPos && !es.deltaDir && glm::dot(es.n, es.n) > 0.0f && !hideEmitters_) {
    if (const auto c = scene.camera.connect(es.p, uLens, scene.pixelFilter.filmMargin())) {
      const auto& area = static_cast<const AreaLight&>(*st.light);
      float value[kMaxLanes];
      for (int j = 0; j < n; ++j) value[j] = area.shape().emission->eval(lanes.lambda[j], es.n, c->wi) * st.start[j];
      if (contributes(ctx, lanes.lambda, value, n) && visible(scene, es.p, es.n, *c, ctx))
        splatLanes(ctx, c->pixel, lanes.lambda, value, n, std::abs(glm::dot(es.n, c->wi)) / es.pdfPos * c->importance * perPath(scene));
    }
  }

  const float magnitude0 = lanes.sum();  // Russian roulette compares the throughput with this
  if (!(magnitude0 > 0.0f)) return Vec3(0.0f);
  Ray ray{glm::dot(es.n, es.n) > 0.0f ? offsetPoint(es.p, es.n, es.w) : es.p, es.w};
  const uint32_t firstDimension = rng.dimension();
  for (int depth = 1; depth <= maxDepth_; ++depth) {
    rng.startVertex(firstDimension, depth - 1);
    const std::optional<Hit> hit = scene.accel->intersect(ray);
    ++ctx.counter.closest;
    if (!hit) break;
    const Bsdf bsdf = scene.bsdf(*hit, {lanes.lambda, size_t(lanes.n)});
    const Vec3 wi = bsdf.toLocal(-ray.d);
    // Spectral stage (Importance) of every lane: the lobe and the wavelengths leaving this vertex.
    const std::span<const float> known(lanes.lambda, size_t(lanes.n));
    const float uLobe = rng.uniform(), uLane = rng.uniform();
    const Vec2 uLens = scene.camera.sampleLens(rng);
    LaneEvent e = sampleLaneEvent(bsdf, TransportMode::Importance, known, n, uLobe, nullptr, atFluorescence_);
    if (e.n == 0) break;
    if (lanesEndAt(e, bsdf)) keepOneLane(e, uLane);

    if (!bsdf.has(BsdfFlags::DeltaDirection)) {
      if (const auto c = scene.camera.connect(hit->p, uLens, scene.pixelFilter.filmMargin())) {
        const Vec3 wo = bsdf.toLocal(c->wi);
        float value[kMaxLanes];
        for (int k = 0; k < e.n; ++k)
          value[k] = laneWeight(bsdf, TransportMode::Importance, known, lanes.beta, e, k, wo, wi) * std::abs(wo.z);
        if (contributes(ctx, e.lambda, value, e.n) && visible(scene, hit->p, hit->ng, *c, ctx))
          splatLanes(ctx, c->pixel, e.lambda, value, e.n, c->importance * perPath(scene));
      }
    }
    if (depth == maxDepth_) break;
    const std::optional<Vec3> w = scatterLightLanes(bsdf, wi, e, lanes, depth >= rrDepth_, magnitude0, rng);
    if (!w) break;
    ray = Ray{offsetPoint(hit->p, hit->ng, *w), *w};
  }
  return Vec3(0.0f);
}

}  // namespace kasha
