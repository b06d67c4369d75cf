#include "integrators/light_tracer.h"

#include "core/color.h"

namespace kasha {
namespace {

// Splats beta·(f·|cos|)·W/(w·h): the film divides by samples per pixel, and there are w·h light
// subpaths per sample per pixel.
void splatToCamera(const Scene& scene, const Camera::Connection& c, float value, float lambda, SampleContext& ctx) {
  const float perPath = 1.0f / (float(scene.camera.width()) * float(scene.camera.height()));
  ctx.splats.push_back(spectralSplat(c.pixel, lambda, value * c.importance * perPath));
}

bool visible(const Scene& scene, const Vec3& p, const Vec3& n, const Camera::Connection& c, SampleContext& ctx) {
  ++ctx.counter.shadow;
  const Vec3 origin = glm::dot(n, n) > 0.0f ? offsetPoint(p, n, c.wi) : p;
  return !scene.accel->occluded(origin, c.wi, c.dist * (1.0f - 1e-4f) - rayEpsilon(p));
}

}  // namespace

LightTracer::LightTracer(const Scene& scene, const RenderSettings& s)
    : wavelengths_(s.wavelengths.light, WavelengthSources(scene), WavelengthSite::LightStart),
      maxDepth_(s.maxDepth),
      rrDepth_(s.rrDepth) {
  requireDensity(s.wavelengths.light, WavelengthSite::LightStart, "for light subpaths");
}

Vec3 LightTracer::samplePixel(const Scene& scene, Vec2, Sampler& rng, SampleContext& ctx) const {
  const LightSelector::LightWavelength lw =
      scene.lightSelector->sampleLightAndWavelength(wavelengths_.density(), rng.uniform(), rng.uniform());
  if (lw.pdf <= 0.0f) return Vec3(0.0f);
  const Light& light = *scene.lights[lw.light];
  const Vec2 uPos = rng.uniform2(), uDir = rng.uniform2();
  const std::optional<EmissionSample> es = light.sampleEmission(lw.lambda, uPos, uDir);
  if (!es || es->pdfPos <= 0.0f || es->pdfDir <= 0.0f) return Vec3(0.0f);

  // The emitter seen directly (area lights; delta lights are not visible to a pinhole).
  if (!es->deltaPos && !es->deltaDir && glm::dot(es->n, es->n) > 0.0f) {
    if (const auto c = scene.camera.connect(es->p)) {
      const auto& area = static_cast<const AreaLight&>(light);
      const float Le = area.shape().emission->eval(lw.lambda, es->n, c->wi);
      if (Le > 0.0f && visible(scene, es->p, es->n, *c, ctx))
        splatToCamera(scene, *c, Le * std::abs(glm::dot(es->n, c->wi)) / (es->pdfPos * lw.pdf), lw.lambda, ctx);
    }
  }

  float beta = es->Le * es->cosOrigin / (es->pdfPos * es->pdfDir * lw.pdf);
  if (!(beta > 0.0f)) return Vec3(0.0f);
  const float beta0 = beta;  // Russian roulette compares the throughput with the emitted weight
  float lambda = lw.lambda;
  Ray ray{glm::dot(es->n, es->n) > 0.0f ? offsetPoint(es->p, es->n, es->w) : es->p, es->w};
  for (int depth = 1; depth <= maxDepth_; ++depth) {
    const std::optional<Hit> hit = scene.accel->intersect(ray);
    ++ctx.counter.closest;
    if (!hit) break;
    const Bsdf bsdf = scene.bsdf(*hit, {&lambda, 1});
    const Vec3 wi = bsdf.toLocal(-ray.d);
    // Spectral stage (Importance): the lobe and the wavelength leaving this vertex.
    const SpectralChoice sc = bsdf.sampleSpectral(TransportMode::Importance, lambda, rng.uniform());
    if (sc.pdf <= 0.0f) break;
    const float lambdaOut = sc.lambda;

    if (!bsdf.has(BsdfFlags::DeltaDirection)) {
      if (const auto c = scene.camera.connect(hit->p)) {
        const Vec3 wo = bsdf.toLocal(c->wi);
        const float f = bsdf.eval(TransportMode::Importance, wi, wo, lambda, lambdaOut, sc.lobe);
        if (f > 0.0f && visible(scene, hit->p, hit->ng, *c, ctx))
          splatToCamera(scene, *c, beta * f * std::abs(wo.z) / sc.pdf, lambdaOut, ctx);
      }
    }
    if (depth == maxDepth_) break;

    const std::optional<DirectionSample> ds =
        bsdf.sampleDirection(TransportMode::Importance, wi, sc.lobe, lambda, lambdaOut, rng.uniform2());
    if (!ds || ds->pdf <= 0.0f) break;
    const float f = bsdf.eval(TransportMode::Importance, wi, ds->w, lambda, lambdaOut, sc.lobe);
    beta *= f * std::abs(ds->w.z) / (sc.pdf * ds->pdf);
    if (!(beta > 0.0f)) break;
    lambda = lambdaOut;
    const Vec3 w = bsdf.toWorld(ds->w);
    ray = Ray{offsetPoint(hit->p, hit->ng, w), w};
    if (depth >= rrDepth_) {
      const float q = std::min(1.0f, beta / beta0);
      if (rng.uniform() >= q) break;
      beta /= q;
    }
  }
  return Vec3(0.0f);
}

}  // namespace kasha
