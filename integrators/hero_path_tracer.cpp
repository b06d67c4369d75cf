#include "integrators/hero_path_tracer.h"

#include <algorithm>
#include <cmath>

#include "core/color.h"
#include "core/sampling.h"
#include "integrators/shadow_ray.h"

namespace kasha {
namespace {

// λ_i of the fluorescent lobe for the hero alone, given its λ_o: the Bsdf's own density (its
// sampleSpectral takes the fluorescent lobe for every u below P_c, then draws λ_i from u/P_c).
WavelengthSample ownExcitation(const Bsdf& bsdf, float lambdaOut, float u) {
  const float pc = bsdf.fluorescenceProbability(TransportMode::Radiance, lambdaOut);
  if (!(pc > 0.0f)) return {};  // the hero's fluorescent lobe is zero: nothing to sample
  const SpectralChoice c = bsdf.sampleSpectral(TransportMode::Radiance, lambdaOut, u * pc);
  if (c.lobe != SpectralLobe::Fluorescent) return {};
  return {c.lambda, c.pdf / pc};
}

}  // namespace

HeroPathTracer::HeroPathTracer(const Scene& scene, const RenderSettings& s)
    : sources_(scene),
      sensor_(s.wavelengths.sensor, sources_, WavelengthSite::Sensor),
      excitation_(s.wavelengths.fluorescence, sources_, scene.materials.size()),
      n_(s.heroWavelengths),
      maxDepth_(s.maxDepth),
      rrDepth_(s.rrDepth) {
  requireDensity(s.wavelengths.sensor, WavelengthSite::Sensor, "with hero wavelengths (their rotations need p)");
  if (!s.wavelengths.nee.uses(WavelengthSpec::Kind::Event))
    throw WavelengthStrategyError(WavelengthSite::Nee, "nee_sampling '" + s.wavelengths.nee.text +
                                                           "' is not supported with hero wavelengths (leave it at 'event')");
  if (n_ < 2 || n_ > kMaxWavelengths)
    throw std::invalid_argument("hero wavelengths: " + std::to_string(n_) + " is outside [2, " +
                                std::to_string(kMaxWavelengths) + "]");
}

float HeroPathTracer::lightSelectProbability(const Scene& scene, size_t light, const Lanes& lanes) const {
  float mine = 0.0f, total = 0.0f;
  for (size_t l = 0; l < scene.lights.size(); ++l)
    for (int j = 0; j < lanes.n; ++j) {
      const float p = scene.lights[l]->power(lanes.lambda[j]);
      total += p;
      if (l == light) mine += p;
    }
  return total > 0.0f ? mine / total : 0.0f;
}

std::pair<size_t, float> HeroPathTracer::selectLight(const Scene& scene, const Lanes& lanes, float u) const {
  float total = 0.0f;
  for (const auto& light : scene.lights)
    for (int j = 0; j < lanes.n; ++j) total += light->power(lanes.lambda[j]);
  if (!(total > 0.0f)) return {0, 0.0f};
  float acc = 0.0f;
  size_t last = 0;
  for (size_t l = 0; l < scene.lights.size(); ++l) {
    float p = 0.0f;
    for (int j = 0; j < lanes.n; ++j) p += scene.lights[l]->power(lanes.lambda[j]);
    if (p <= 0.0f) continue;
    last = l;
    acc += p;
    if (u * total < acc) return {l, p / total};
  }
  return {last, lightSelectProbability(scene, last, lanes)};
}

Vec3 HeroPathTracer::samplePixel(const Scene& scene, Vec2 pixel, Sampler& rng, SampleContext& ctx) const {
  const WavelengthDensity& p = sensor_.density();
  const WavelengthSample hero = p.sample(rng.uniform());
  const Vec2 jitter = rng.uniform2();
  if (hero.pdf <= 0.0f) return Vec3(0.0f);
  // Wilkie14 §3: the rotations of the hero over the sensor's range.
  const WavelengthRange r = sources_.seen;
  Lanes lanes;
  lanes.n = n_;
  float pSum = 0.0f;
  for (int j = 0; j < n_; ++j) {
    const float shifted = std::fmod(hero.lambda - r.min + float(j) * r.width() / float(n_), r.width());
    lanes.lambda[j] = std::clamp(r.min + shifted, r.min, r.max);
    lanes.beta[j] = 1.0f;
    lanes.L[j] = 0.0f;
    pSum += p.pdf(lanes.lambda[j]);
  }
  float lambdas[kMaxWavelengths];
  std::copy(lanes.lambda, lanes.lambda + n_, lambdas);
  radiance(scene, scene.camera.generateRay(pixel + jitter), lanes, pSum / hero.pdf, rng, ctx.counter);
  // Balance heuristic over the N hero techniques (Wilkie14 eq. 8): W(λ_j)·L_j / Σ_k p(λ_k).
  Vec3 xyz(0.0f);
  for (int j = 0; j < n_; ++j) xyz += sensorResponse(ctx, lambdas[j], lanes.L[j] / pSum);
  return xyz;
}

void HeroPathTracer::radiance(const Scene& scene, Ray ray, Lanes& s, float collapseFactor, Sampler& rng,
                              RayCounter& counter) const {
  float beta0 = 1.0f;          // Russian roulette compares the throughput with this
  float prevDirPdf = 0.0f;     // solid-angle density of the direction that led here
  bool prevSpecular = true;    // the camera ray counts as specular: no MIS on direct hits
  Vec3 prevP = ray.o;
  Lanes prevSelect;            // the wavelengths next-event estimation chose its light with at the last vertex
  // Mojzík18: the secondary wavelengths end; the hero alone is now weighted by 1/p(λ_h).
  auto collapse = [&] {
    if (s.n == 1) return;
    s.n = 1;
    s.beta[0] *= collapseFactor;
    beta0 *= collapseFactor;
  };
  const uint32_t firstDimension = rng.dimension();
  for (int depth = 0;; ++depth) {
    rng.startVertex(firstDimension, depth);
    const std::optional<Hit> hit = scene.accel->intersect(ray);
    ++counter.closest;
    if (!hit) {
      if (const EnvironmentLight* env = scene.environment()) {
        float w = 1.0f;
        if (!prevSpecular)
          w = powerHeuristic(prevDirPdf,
                             lightSelectProbability(scene, size_t(scene.environmentLight), prevSelect) * env->pdfDirection(ray.d));
        for (int j = 0; j < s.n; ++j) s.L[j] += s.beta[j] * env->Le(s.lambda[j], ray.d) * w;
      }
      break;
    }
    const Shape& shape = scene.shapes[hit->shape];
    if (shape.emission) {
      float w = 1.0f;
      if (!prevSpecular) {
        const size_t li = size_t(scene.shapeLight[hit->shape]);
        w = powerHeuristic(prevDirPdf,
                           lightSelectProbability(scene, li, prevSelect) * scene.lights[li]->pdfLi(prevP, hit->p, hit->ng));
      }
      for (int j = 0; j < s.n; ++j) s.L[j] += s.beta[j] * shape.emission->eval(s.lambda[j], hit->ng, -ray.d) * w;
    }
    if (depth >= maxDepth_) break;

    const Bsdf bsdf = scene.bsdf(*hit, {s.lambda, size_t(s.n)});
    const Vec3 wo = bsdf.toLocal(-ray.d);
    // Spectral stage, symmetric in the lanes: the fluorescent lobe with the mean of their P_c.
    float pFluor = 0.0f;
    if (bsdf.has(BsdfFlags::Fluorescent)) {
      for (int j = 0; j < s.n; ++j) pFluor += bsdf.fluorescenceProbability(TransportMode::Radiance, s.lambda[j]);
      pFluor /= float(s.n);
    }
    const float u = rng.uniform();
    SpectralLobe lobe = SpectralLobe::Elastic;
    float spectralPdf = 1.0f - pFluor;
    float lambdaIn[kMaxWavelengths];
    std::copy(s.lambda, s.lambda + s.n, lambdaIn);
    if (u < pFluor) {
      collapse();
      const float v = std::min(u / pFluor, 0x1.fffffep-1f);
      const WavelengthSample ex = excitation_.draws(shape.material) ? excitation_.sampleExcitation(shape.material, v)
                                                                    : ownExcitation(bsdf, s.lambda[0], v);
      if (ex.pdf <= 0.0f) break;
      lobe = SpectralLobe::Fluorescent;
      spectralPdf = pFluor * ex.pdf;
      lambdaIn[0] = ex.lambda;
    }
    if (!(spectralPdf > 0.0f)) break;
    // The lanes share one direction sample only where its density is the same for every lane
    // (pbrt-v4's SampledWavelengths::TerminateSecondary): next-event estimation below weights all
    // of them with the hero's direction density, so the secondaries end before it.
    if (bsdf.has(BsdfFlags::WavelengthDependentDirection)) collapse();

    // Next-event estimation for every lane through one light sample.
    const float uLight = rng.uniform();
    const Vec2 uPos = rng.uniform2();
    prevSelect.n = s.n;
    std::copy(lambdaIn, lambdaIn + s.n, prevSelect.lambda);
    if (!bsdf.has(BsdfFlags::DeltaDirection)) {
      const auto [li, pSelect] = selectLight(scene, prevSelect, uLight);
      const std::optional<LightSample> ls =
          pSelect > 0.0f ? scene.lights[li]->sampleLi(hit->p, lambdaIn[0], uPos) : std::nullopt;
      if (ls && ls->pdf > 0.0f) {
        const Vec3 wi = bsdf.toLocal(ls->wi);
        if (lightVisible(scene, *hit, *ls, counter)) {
          const float lightPdf = pSelect * ls->pdf;
          const float w = ls->delta ? 1.0f
                                    : powerHeuristic(lightPdf, bsdf.directionPdf(TransportMode::Radiance, wo, wi, lobe,
                                                                                 lambdaIn[0], s.lambda[0]));
          for (int j = 0; j < s.n; ++j) {
            // The light's geometry does not depend on λ: the same point at every lane's wavelength.
            const std::optional<LightSample> lj = j == 0 ? ls : scene.lights[li]->sampleLi(hit->p, lambdaIn[j], uPos);
            const float f = bsdf.eval(TransportMode::Radiance, wi, wo, lambdaIn[j], s.lambda[j], lobe);
            if (lj) s.L[j] += s.beta[j] * (f * std::abs(wi.z) / spectralPdf) * lj->Li * w / lightPdf;
          }
        }
      }
    }

    // Direction stage, sampled at the hero's wavelengths; every remaining lane has the same density.
    const std::optional<DirectionSample> ds = bsdf.sampleDirection(TransportMode::Radiance, wo, lobe, lambdaIn[0],
                                                                   s.lambda[0], rng.uniform2());
    if (!ds || ds->pdf <= 0.0f) break;
    if (ds->specular) collapse();
    float maxBeta = 0.0f;
    for (int j = 0; j < s.n; ++j) {
      const float f = bsdf.eval(TransportMode::Radiance, ds->w, wo, lambdaIn[j], s.lambda[j], lobe);
      s.beta[j] *= f * std::abs(ds->w.z) / (spectralPdf * ds->pdf);
      s.lambda[j] = lambdaIn[j];
      maxBeta = std::max(maxBeta, s.beta[j]);
    }
    if (!(maxBeta > 0.0f)) break;
    prevDirPdf = ds->pdf;
    prevSpecular = ds->specular;
    prevP = hit->p;
    const Vec3 wiWorld = bsdf.toWorld(ds->w);
    ray = Ray{offsetPoint(hit->p, hit->ng, wiWorld), wiWorld};

    // Russian roulette on the largest lane's throughput (every lane divided by the same q).
    if (depth + 1 >= rrDepth_) {
      const float q = std::min(1.0f, maxBeta / beta0);
      if (rng.uniform() >= q) break;
      for (int j = 0; j < s.n; ++j) s.beta[j] /= q;
    }
  }
}

}  // namespace kasha
