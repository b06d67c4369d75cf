#include "integrators/light_tracing/light_tracer.h"

#include <algorithm>

#include "core/color.h"
#include "integrators/light_subpath_lanes.h"
#include "integrators/medium_transport.h"

namespace kasha {
namespace {

// The film divides by samples per pixel, and there are w·h light subpaths per sample per pixel.
float perPath(const Scene& scene) { return 1.0f / (float(scene.camera.width()) * float(scene.camera.height())); }

// The transmittance of every lane from vertex v (a surface point, or a medium point with ng = 0)
// to the camera point of c; false if a surface blocks it.
bool cameraTransmittance(const Scene& scene, const Hit& v, VertexMedium where, const Camera::Connection& c,
                         std::span<const float> lambda, float* tr, SampleContext& ctx) {
  return segmentTransmittance(scene, offsetPoint(v.p, v.ng, c.wi), c.wi, c.dist * (1.0f - 1e-4f) - rayEpsilon(v.p),
                              where.leaving(scene, v, c.wi), lambda, tr, ctx.counter);
}

// The sensor's XYZ response W(λ_k) to each lane, where the film keeps XYZ alone (with spectral bins
// each splat finds its own).
void laneResponses(const SampleContext& ctx, const float* lambda, int n, Vec3* W) {
  if (!ctx.recordSpectral)
    for (int k = 0; k < n; ++k) W[k] = Observer::cie1931().weight(lambda[k]);
}

// The XYZ of the lanes' values, Σ_k W(λ_k)·value[k].
Vec3 lanesXyz(const Vec3* W, const float* value, int n) {
  Vec3 xyz(0.0f);
  for (int k = 0; k < n; ++k) xyz += W[k] * value[k];
  return xyz;
}

// Whether the lanes add anything the film keeps: XYZ, and with spectral bins any lane's value.
bool contributes(const SampleContext& ctx, const Vec3* W, const float* value, int n) {
  if (ctx.recordSpectral) return std::any_of(value, value + n, [](float v) { return v != 0.0f; });
  return lanesXyz(W, value, n) != Vec3(0.0f);
}

// Splats the lanes' values, each times `scale`: as one XYZ splat, or with spectral bins one splat
// per lane, so that each bin gets its lane's share.
void splatLanes(SampleContext& ctx, Vec2 pixel, const float* lambda, const Vec3* W, const float* value, int n,
                float scale) {
  if (!ctx.recordSpectral) {
    ctx.splats.push_back({pixel, lanesXyz(W, value, n) * scale});
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
  const auto [origin, atLight] = lightOrigin(scene, st);

  // The emitter seen directly (area lights; delta lights have no area the camera could see).
  if (!es.deltaPos && !es.deltaDir && glm::dot(es.n, es.n) > 0.0f && !hideEmitters_) {
    if (const auto c = scene.camera.connect(es.p, uLens, scene.pixelFilter.filmMargin())) {
      const auto& area = static_cast<const AreaLight&>(*st.light);
      float value[kMaxLanes], tr[kMaxLanes];
      Vec3 W[kMaxLanes];
      for (int j = 0; j < n; ++j) value[j] = area.shape().emission->eval(lanes.lambda[j], es.n, c->wi) * st.start[j];
      laneResponses(ctx, lanes.lambda, n, W);
      if (contributes(ctx, W, value, n) &&
          cameraTransmittance(scene, origin, atLight, *c, {lanes.lambda, size_t(n)}, tr, ctx)) {
        for (int j = 0; j < n; ++j) value[j] *= tr[j];
        splatLanes(ctx, c->pixel, lanes.lambda, W, value, n,
                   std::abs(glm::dot(es.n, c->wi)) / es.pdfPos * c->importance * perPath(scene));
      }
    }
  }

  const float magnitude0 = magnitude(lanes);  // Russian roulette compares the throughput with this
  if (!(magnitude0 > 0.0f)) return Vec3(0.0f);
  Ray ray{offsetPoint(es.p, es.n, es.w), es.w};
  // Media (docs/media.md §3): the medium the ray travels in, and the lanes' spectral MIS of free flights.
  const bool media = scene.hasMedia();
  int medium = atLight.leaving(scene, origin, es.w);
  LaneRatios ratios;
  ratios.reset(lanes.n);
  const uint32_t firstDimension = rng.dimension();
  for (int depth = 1; depth <= maxDepth_; ++depth) {
    const std::optional<LightSubpathVertex> v = nextLightVertex(scene, ray, medium, lanes, ratios, rng, firstDimension, depth, ctx.counter);
    if (!v) break;
    const auto& [vertex, where, bsdf, mis] = *v;
    const Vec3 wi = bsdf.toLocal(-ray.d);
    // Spectral stage (Importance) of every lane: the lobe and the wavelengths leaving this vertex.
    const std::span<const float> known(lanes.lambda, size_t(lanes.n));
    const float uLobe = rng.uniform(), uLane = rng.uniform();
    const Vec2 uLens = scene.camera.sampleLens(rng);
    LaneEvent e = sampleLaneEvent(bsdf, TransportMode::Importance, known, n, uLobe, nullptr, atFluorescence_);
    if (e.n == 0) break;
    if (lanesEndAt(e, bsdf)) keepOneLane(e, uLane);

    if (!bsdf.has(BsdfFlags::DeltaDirection)) {
      if (const auto c = scene.camera.connect(vertex.p, uLens, scene.pixelFilter.filmMargin())) {
        const Vec3 wo = bsdf.toLocal(c->wi);
        float value[kMaxLanes], tr[kMaxLanes];
        Vec3 W[kMaxLanes];
        for (int k = 0; k < e.n; ++k)
          value[k] = laneWeight(bsdf, TransportMode::Importance, known, lanes.beta, e, k, wo, wi) * bsdf.cosineFactor(wo);
        laneResponses(ctx, e.lambda, e.n, W);
        if (contributes(ctx, W, value, e.n) &&
            cameraTransmittance(scene, vertex, where, *c, {e.lambda, size_t(e.n)}, tr, ctx)) {
          for (int k = 0; k < e.n; ++k) value[k] *= tr[k] * mis;
          splatLanes(ctx, c->pixel, e.lambda, W, value, e.n, c->importance * perPath(scene));
        }
      }
    }
    if (depth == maxDepth_) break;
    // Fresh lanes (fluorescent), or one lane kept: the free flights' MIS so far goes into them.
    if (media && (e.lobe == SpectralLobe::Fluorescent || e.n != lanes.n)) {
      for (int k = 0; k < lanes.n; ++k) lanes.beta[k] *= mis;
      ratios.reset(e.n);
    }
    const std::optional<Vec3> w = scatterLightLanes(bsdf, wi, e, lanes, depth >= rrDepth_, magnitude0, rng);
    if (!w) break;
    ray = Ray{offsetPoint(vertex.p, vertex.ng, *w), *w};
    if (media) medium = where.leaving(scene, vertex, *w);
  }
  return Vec3(0.0f);
}

}  // namespace kasha
