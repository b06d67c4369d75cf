#include "integrators/path_tracing/path_tracer.h"

#include "core/color.h"
#include "core/sampling.h"
#include "integrators/shadow_ray.h"

namespace kasha {

PathTracer::PathTracer(const Scene& scene, const RenderSettings& s)
    : sources_(scene),
      sensor_(s.wavelengths.sensor, sources_, WavelengthSite::Sensor),
      fluorescence_(s.wavelengths.fluorescence, sources_, scene.materials.size()),
      nee_(s.wavelengths.nee, sources_, scene.materials.size(), WavelengthSite::Nee),
      maxDepth_(s.maxDepth),
      rrDepth_(s.rrDepth) {}

Vec3 PathTracer::samplePixel(const Scene& scene, Vec2 pixel, Sampler& rng, SampleContext& ctx) const {
  Vec3 xyz(0.0f);
  for (int i = 0; i < sensor_.samplesPerEstimate(); ++i) {
    const WavelengthStrategy::Draw d = sensor_.draw(i, rng.uniform());
    const Vec2 jitter = rng.uniform2();
    if (!(d.weight > 0.0f)) continue;
    const Ray ray = scene.camera.generateRay(pixel + jitter);
    const float L = radiance(scene, ray, d.lambda, rng, ctx.counter);
    // W(λ)·L(λ)·(MIS weight)/p(λ): the sensor responds at the wavelength arriving at it (transport.md §1).
    xyz += sensorResponse(ctx, d.lambda, L * d.weight);
  }
  return xyz;
}

float PathTracer::radiance(const Scene& scene, Ray ray, float lambda, Sampler& rng, RayCounter& counter) const {
  const LightSelector& lights = *scene.lightSelector;
  float L = 0.0f, beta = 1.0f;
  float prevDirPdf = 0.0f;     // solid-angle density of the direction that led here
  // The spectral event's density at the last vertex, and the one next-event estimation had for
  // the same λ_i (they differ only for a fluorescent event with its own nee_sampling).
  float prevSpectralPdf = 1.0f, prevNeeSpectralPdf = 1.0f;
  bool prevSpecular = true;    // the camera ray counts as specular: no MIS on direct hits
  Vec3 prevP = ray.o;
  const uint32_t firstDimension = rng.dimension();
  for (int depth = 0;; ++depth) {
    rng.startVertex(firstDimension, depth);
    const std::optional<Hit> hit = scene.accel->intersect(ray);
    ++counter.closest;
    if (!hit) {
      if (const EnvironmentLight* env = scene.environment()) {
        const float Le = env->Le(lambda, ray.d);
        float w = 1.0f;
        if (!prevSpecular) {
          const float lightPdf = lights.probability(size_t(scene.environmentLight), lambda) * env->pdfDirection(ray.d);
          w = powerHeuristic(prevDirPdf * prevSpectralPdf, lightPdf * prevNeeSpectralPdf);
        }
        L += beta * Le * w;
      }
      break;
    }
    const Shape& shape = scene.shapes[hit->shape];
    if (shape.emission) {
      const float Le = shape.emission->eval(lambda, hit->ng, -ray.d);
      if (Le > 0.0f) {
        float w = 1.0f;
        if (!prevSpecular) {
          const size_t li = size_t(scene.shapeLight[hit->shape]);
          const float lightPdf = lights.probability(li, lambda) * scene.lights[li]->pdfLi(prevP, hit->p, hit->ng);
          w = powerHeuristic(prevDirPdf * prevSpectralPdf, lightPdf * prevNeeSpectralPdf);
        }
        L += beta * Le * w;
      }
    }
    if (depth >= maxDepth_) break;

    const Bsdf bsdf = scene.bsdf(*hit, {&lambda, 1});
    const Vec3 wo = bsdf.toLocal(-ray.d);
    // Spectral stage: lobe and the wavelength the light had before this vertex.
    const SpectralChoice sc = fluorescence_.sample(bsdf, shape.material, lambda, rng.uniform());
    if (sc.pdf <= 0.0f) break;
    const float lambdaIn = sc.lambda;

    // Next-event estimation at λ_i, or after a fluorescent event at a wavelength of its own
    // (nee_sampling). Its MIS weight then compares full densities, wavelength included: the light
    // sample's P_c·p_nee(λ)·p_light against the event's P_c·p_event(λ)·p_dir.
    prevSpectralPdf = prevNeeSpectralPdf = sc.pdf;
    float lambdaNee = lambdaIn, neeSpectralPdf = sc.pdf, eventPdfAtNee = sc.pdf;
    const bool ownNee = sc.lobe == SpectralLobe::Fluorescent && nee_.draws(shape.material);
    if (ownNee) {
      const WavelengthSample ws = nee_.sampleExcitation(shape.material, rng.uniform());
      lambdaNee = ws.lambda;
      neeSpectralPdf = ws.pdf > 0.0f ? bsdf.fluorescenceProbability(TransportMode::Radiance, lambda) * ws.pdf : 0.0f;
      eventPdfAtNee = fluorescence_.pdf(bsdf, shape.material, lambda, lambdaNee, SpectralLobe::Fluorescent);
      prevNeeSpectralPdf = nee_.pdf(bsdf, shape.material, lambda, lambdaIn, SpectralLobe::Fluorescent);
    }
    const float uLight = rng.uniform();
    const Vec2 uPos = rng.uniform2();
    if (!bsdf.has(BsdfFlags::DeltaDirection) && neeSpectralPdf > 0.0f) {
      const auto [li, pSelect] = lights.select(lambdaNee, uLight);
      if (pSelect > 0.0f) {
        const std::optional<LightSample> ls = scene.lights[li]->sampleLi(hit->p, lambdaNee, uPos);
        if (ls && ls->Li > 0.0f && ls->pdf > 0.0f) {
          const Vec3 wi = bsdf.toLocal(ls->wi);
          const float f = bsdf.eval(TransportMode::Radiance, wi, wo, lambdaNee, lambda, sc.lobe);
          if (f > 0.0f) {
            if (lightVisible(scene, *hit, *ls, counter)) {
              const float lightPdf = pSelect * ls->pdf;
              const float dirPdf = bsdf.directionPdf(TransportMode::Radiance, wo, wi, sc.lobe, lambdaNee, lambda);
              const float w =
                  ls->delta ? 1.0f : powerHeuristic(lightPdf * neeSpectralPdf, dirPdf * eventPdfAtNee);
              L += beta * (f * std::abs(wi.z) / neeSpectralPdf) * ls->Li * w / lightPdf;
            }
          }
        }
      }
    }

    // Direction stage.
    const std::optional<DirectionSample> ds =
        bsdf.sampleDirection(TransportMode::Radiance, wo, sc.lobe, lambdaIn, lambda, rng.uniform2());
    if (!ds || ds->pdf <= 0.0f) break;
    const float f = bsdf.eval(TransportMode::Radiance, ds->w, wo, lambdaIn, lambda, sc.lobe);
    beta *= f * std::abs(ds->w.z) / (sc.pdf * ds->pdf);
    if (!(beta > 0.0f)) break;
    prevDirPdf = ds->pdf;
    prevSpecular = ds->specular;
    prevP = hit->p;
    lambda = lambdaIn;
    const Vec3 wiWorld = bsdf.toWorld(ds->w);
    ray = Ray{offsetPoint(hit->p, hit->ng, wiWorld), wiWorld};

    // Russian roulette on the throughput.
    if (depth + 1 >= rrDepth_) {
      const float q = std::min(1.0f, beta);
      if (rng.uniform() >= q) break;
      beta /= q;
    }
  }
  return L;
}

}  // namespace kasha
