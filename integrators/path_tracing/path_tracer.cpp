#include "integrators/path_tracing/path_tracer.h"

#include <algorithm>
#include <cmath>
#include <type_traits>

#include "core/color.h"
#include "core/sampling.h"
#include "integrators/direct_emission.h"
#include "integrators/lane_light_choice.h"
#include "integrators/lane_next_event.h"
#include "integrators/medium_transport.h"

namespace kasha {
namespace {

// The event of one lane, which goes on as itself, from its spectral choice; none if its density is 0.
LaneEvent oneLaneEvent(const SpectralChoice& c) {
  LaneEvent e;
  if (!(c.pdf > 0.0f)) return e;
  e.lobe = c.lobe;
  e.n = 1;
  e.lambda[0] = c.lambda;
  e.scale[0] = 1.0f / c.pdf;
  e.source[0] = 0;
  e.odds[0] = 1.0f;
  return e;
}

}  // namespace

PathTracer::PathTracer(const Scene& scene, const RenderSettings& s)
    : sources_(scene),
      sensor_(s.wavelengths.sensor, sources_, WavelengthSite::Sensor),
      excitation_(s.wavelengths.fluorescence, sources_, scene.materials.size()),
      nee_(s.wavelengths.nee, sources_, scene.materials.size(), WavelengthSite::Nee),
      n_(s.heroWavelengths),
      atFluorescence_(s.fluorescentLanes),
      maxDepth_(s.maxDepth),
      rrDepth_(s.rrDepth),
      hideEmitters_(s.hideEmitters),
      directXyz_(directEmissionXyz(scene)) {
  if (n_ == 1) return;  // one wavelength: any sensor, fluorescence and nee strategy
  requireDensity(s.wavelengths.sensor, WavelengthSite::Sensor, "with hero wavelengths (their strata need p)");
  requireLaneSettings(s, n_, 2, "hero wavelengths");
}

Vec3 PathTracer::samplePixel(const Scene& scene, Vec2 pixel, Sampler& rng, SampleContext& ctx) const {
  if (n_ == 1) {
    // One path per draw of the sensor strategy, its lane's throughput (MIS weight)/p(λ); the sensor
    // responds with W(λ) at the wavelength arriving at it (transport.md §1).
    Vec3 xyz(0.0f);
    for (int i = 0; i < sensor_.samplesPerEstimate(); ++i) {
      const WavelengthStrategy::Draw d = sensor_.draw(i, rng.uniform());
      const Vec2 uFilm = rng.uniform2();
      const Vec2 uLens = scene.camera.sampleLens(rng);
      if (!(d.weight > 0.0f)) continue;
      PathLanes<float> lane;
      lane.n = 1;
      lane.lambda[0] = d.lambda;
      lane.beta[0] = d.weight;
      const Ray ray = scene.camera.generateRay(scene.pixelFilter.filmPosition(pixel, uFilm), uLens);
      const float L = radiance(scene, ray, lane, rng, ctx.counter);
      xyz += sensorResponse(ctx, d.lambda, L);
    }
    return xyz;
  }
  // Lane j at the stratum (u + j/N) of the sensor density p: distributed as p, weighted by 1/(N·p(λ_j)).
  const SampledLanes sampled = sampleLanes(sensor_.density(), rng.uniform(), n_);
  const float* lambda = sampled.lambda;
  const float* pdf = sampled.pdf;
  const Vec2 uFilm = rng.uniform2();
  const Vec2 uLens = scene.camera.sampleLens(rng);
  const Ray ray = scene.camera.generateRay(scene.pixelFilter.filmPosition(pixel, uFilm), uLens);
  if (!ctx.recordSpectral) {
    // The lanes' XYZ throughput W(λ_j)/(N·p(λ_j)).
    PathLanes<Vec3> lanes;
    lanes.n = n_;
    for (int j = 0; j < n_; ++j) {
      lanes.lambda[j] = lambda[j];
      lanes.beta[j] = pdf[j] > 0.0f ? Observer::cie1931().weight(lambda[j]) / (float(n_) * pdf[j]) : Vec3(0.0f);
    }
    return radiance(scene, ray, lanes, rng, ctx.counter);
  }
  // Each lane in its own share of the sensor, which responds at the end (transport.md §1).
  CameraLanes lanes;
  lanes.n = n_;
  for (int j = 0; j < n_; ++j) {
    lanes.lambda[j] = lambda[j];
    lanes.beta[j].v[j] = pdf[j] > 0.0f ? 1.0f / (float(n_) * pdf[j]) : 0.0f;
  }
  const SensorShares L = radiance(scene, ray, lanes, rng, ctx.counter);
  Vec3 xyz(0.0f);
  for (int j = 0; j < n_; ++j)
    if (L.v[j] != 0.0f) xyz += sensorResponse(ctx, lambda[j], L.v[j]);
  return xyz;
}

template <class T>
T PathTracer::radiance(const Scene& scene, Ray ray, PathLanes<T>& lanes, Sampler& rng, RayCounter& counter) const {
  constexpr bool oneLane = std::is_same_v<T, float>;
  T L = lanes.beta[0] * 0.0f;
  const float magnitude0 = magnitude(lanes);  // Russian roulette compares the throughput with this
  float prevDirPdf = 0.0f;     // solid-angle density of the direction that led here
  // The wavelength density of the last vertex's event for the λ_i the path took, and the one
  // next-event estimation had for it: they differ only where next-event estimation drew its own λ_i
  // (nee_sampling, N = 1); elsewhere both are left at 1, being the same (they cancel).
  float prevSpectralPdf = 1.0f, prevNeeSpectralPdf = 1.0f;
  bool prevSpecular = true;    // the camera ray counts as specular: no MIS on direct hits
  Vec3 prevP = ray.o;
  // Next-event estimation's light choice for the lanes at this vertex and at the last one (the
  // emitter-hit MIS weight needs its P(l)). One lane takes the scene's at its wavelength instead.
  thread_local LaneLightChoice lightChoice[2];
  int current = 0;
  const auto lastLightProbability = [&](size_t light) {
    if constexpr (oneLane) return scene.lightSelector->probability(light, lanes.lambda[0]);
    else return lightChoice[current ^ 1].probability(light);
  };
  // Media (docs/media.md §3): the medium the ray travels in, and the lanes' spectral MIS of free flights.
  const bool media = scene.hasMedia();
  int medium = scene.cameraMedium;
  LaneRatios ratios;
  ratios.reset(lanes.n);
  const uint32_t firstDimension = rng.dimension();
  for (int depth = 0;; ++depth) {
    rng.startVertex(firstDimension, depth);
    const float uFlight = media ? freeFlightUniform(rng, firstDimension, depth) : 0.0f;
    const FreeFlight flight = traceFreeFlight(scene, ray, medium, {lanes.lambda, size_t(lanes.n)}, uFlight, TransportMode::Radiance, counter);
    float mis = 1.0f;  // every contribution's share of the lanes' spectral MIS (LaneRatios)
    if (media) {
      for (int k = 0; k < lanes.n; ++k) {
        lanes.beta[k] = lanes.beta[k] * flight.weight[k];
        ratios.r[k] *= flight.ratio[k];
      }
      mis = ratios.misWeight();
    }
    const std::optional<Hit>& hit = flight.hit;
    const bool seesEmitters = depth > 0 || !hideEmitters_;
    if (!hit && !flight.collided) {
      if (const EnvironmentLight* env = seesEmitters ? scene.environment() : nullptr) {
        float w = 1.0f;
        if (!prevSpecular)
          w = powerHeuristic(prevDirPdf * prevSpectralPdf, lastLightProbability(size_t(scene.environmentLight)) *
                                                               env->pdfDirection(ray.d) * prevNeeSpectralPdf);
        for (int j = 0; j < lanes.n; ++j) L += lanes.beta[j] * (env->Le(lanes.lambda[j], ray.d) * w * mis);
      }
      break;
    }
    // A surface, or a point in a medium (no shape, no normal: offsetPoint leaves it where it is).
    const Shape* shape = flight.collided ? nullptr : &scene.shapes[hit->shape];
    Hit mediumPoint;
    if (!shape) mediumPoint.p = flight.p, mediumPoint.ng = Vec3(0.0f);
    const Hit& vertex = shape ? *hit : mediumPoint;
    if (shape && shape->emission && seesEmitters) {
      float w = 1.0f;
      if (!prevSpecular) {
        const size_t li = size_t(scene.shapeLight[hit->shape]);
        w = powerHeuristic(prevDirPdf * prevSpectralPdf, lastLightProbability(li) *
                                                             scene.lights[li]->pdfLi(prevP, hit->p, hit->ng) *
                                                             prevNeeSpectralPdf);
      }
      // Seen directly, an area emitter's L_e(λ)·[side] is known at every λ: its XYZ is exact.
      // Spectral bins need each lane's share, and one lane its wavelength: there the lanes estimate it.
      // (Through a medium, the lanes estimate its transmittance too.)
      if (depth > 0 || media || !std::is_same_v<T, Vec3>) {
        for (int j = 0; j < lanes.n; ++j)
          L += lanes.beta[j] * (shape->emission->eval(lanes.lambda[j], hit->ng, -ray.d) * w * mis);
      } else if constexpr (std::is_same_v<T, Vec3>) {
        if (shape->emission->emitsTowards(hit->ng, -ray.d)) L += directXyz_[size_t(scene.shapeLight[hit->shape])];
      }
    }
    if (depth >= maxDepth_) break;

    const Bsdf bsdf = shape ? scene.bsdf(*hit, {lanes.lambda, size_t(lanes.n)}) : scene.mediumBsdf(flight.medium, flight.p);
    const VertexMedium where{flight.medium, shape != nullptr};
    const Vec3 wo = bsdf.toLocal(-ray.d);
    const float uLobe = rng.uniform();
    const float uLane = oneLane ? 0.0f : rng.uniform();  // the lane kept where the lanes end
    const std::span<const float> known(lanes.lambda, size_t(lanes.n));
    // The lobe and λ_i (Jung18 eq. 7's P_c, then the fluorescence strategy or the material's own
    // density): one lane samples them as sampleLaneEvent would with N = 1, without its mixture.
    // A medium's collision samples its own (the fluorescence strategies are the surfaces').
    const bool strategy = shape && excitation_.draws(shape->material);
    LaneEvent e = oneLane ? oneLaneEvent(shape ? excitation_.sample(bsdf, shape->material, lanes.lambda[0], uLobe)
                                               : bsdf.sampleSpectral(TransportMode::Radiance, lanes.lambda[0], uLobe))
                          : sampleLaneEvent(bsdf, TransportMode::Radiance, known, n_, uLobe,
                                            strategy ? &excitation_.density(shape->material) : nullptr, atFluorescence_);
    if (e.n == 0) break;
    // The lanes share one direction sample only where its density is the same for every lane:
    // next-event estimation below weights all of them with one direction density. (And they end
    // at a fluorescent event with --fluorescent-lanes end.) One lane has nothing to end.
    if (!oneLane && lanesEndAt(e, bsdf)) keepOneLane(e, uLane);
    // Direction sampling uses lane 0's wavelengths (the density is every lane's).
    const float lambdaOut0 = e.lobe == SpectralLobe::Elastic ? e.lambda[0] : lanes.lambda[0];

    // Next-event estimation for every lane through one light sample. One lane (nee_sampling needs
    // N = 1), after a fluorescent event with an nee strategy: with a λ_i of its own, its MIS weight
    // comparing full densities, wavelength included: the light sample's P_c·p_nee(λ)·p_light against
    // the event's P_c·p_event(λ)·p_dir.
    const bool ownNee = oneLane && shape && e.lobe == SpectralLobe::Fluorescent && nee_.draws(shape->material);
    const float uNee = ownNee ? rng.uniform() : 0.0f;
    const float uLight = rng.uniform();
    const Vec2 uPos = rng.uniform2();
    prevSpectralPdf = prevNeeSpectralPdf = 1.0f;
    if constexpr (oneLane) {
      LaneEvent own;
      NeeSpectralPdfs spectral;
      if (ownNee) {
        const WavelengthSample ws = nee_.sampleExcitation(shape->material, uNee);
        spectral.nee = ws.pdf > 0.0f ? bsdf.fluorescenceProbability(TransportMode::Radiance, lambdaOut0) * ws.pdf : 0.0f;
        spectral.event = excitation_.pdf(bsdf, shape->material, lambdaOut0, ws.lambda, e.lobe);
        own = e;
        own.lambda[0] = ws.lambda;
        own.scale[0] = spectral.nee > 0.0f ? 1.0f / spectral.nee : 0.0f;
        prevSpectralPdf = excitation_.pdf(bsdf, shape->material, lambdaOut0, e.lambda[0], e.lobe);
        prevNeeSpectralPdf = nee_.pdf(bsdf, shape->material, lambdaOut0, e.lambda[0], e.lobe);
      }
      const LaneEvent& nee = ownNee ? own : e;
      L += laneNextEvent(scene, vertex, where, bsdf, wo, known, lanes.beta, nee,
                         OneLaneLightChoice{*scene.lightSelector, nee.lambda[0]}, lambdaOut0, uLight, uPos,
                         NeeWeight::PowerHeuristic, counter, spectral) * mis;
    } else {
      LaneLightChoice& lights = lightChoice[current];
      if (!bsdf.has(BsdfFlags::DeltaDirection)) {
        float before[kMaxLanes], importance[kMaxLanes];
        for (int j = 0; j < lanes.n; ++j) before[j] = magnitude(lanes.beta[j]);
        laneImportance(bsdf, TransportMode::Radiance, known, before, e, importance);
        lights.reset(scene, {e.lambda, size_t(e.n)}, importance);
      }
      L += laneNextEvent(scene, vertex, where, bsdf, wo, known, lanes.beta, e, lights, lambdaOut0, uLight, uPos,
                         NeeWeight::PowerHeuristic, counter) * mis;
    }

    // Direction stage at lane 0's wavelengths; every lane has the same density.
    const std::optional<DirectionSample> ds =
        bsdf.sampleDirection({TransportMode::Radiance, e.lobe, e.lambda[0], lambdaOut0}, wo, rng.uniform2());
    if (!ds || ds->pdf <= 0.0f) break;
    T next[kMaxLanes];
    for (int k = 0; k < e.n; ++k)
      next[k] = laneWeight(bsdf, TransportMode::Radiance, known, lanes.beta, e, k, ds->w, wo) * (bsdf.cosineFactor(ds->w) / ds->pdf);
    // Fresh lanes (fluorescent), or one lane kept: the free flights' MIS so far goes into them.
    if (media && (e.lobe == SpectralLobe::Fluorescent || e.n != lanes.n)) {
      for (int k = 0; k < e.n; ++k) next[k] = next[k] * mis;
      ratios.reset(e.n);
    }
    lanes.n = e.n;
    float m = 0.0f;  // their magnitude
    for (int k = 0; k < e.n; ++k) {
      lanes.lambda[k] = e.lambda[k];
      lanes.beta[k] = next[k];
      m += magnitude(next[k]);
    }
    if (!(m > 0.0f)) break;
    prevDirPdf = ds->pdf;
    prevSpecular = ds->specular;
    current ^= 1;
    prevP = vertex.p;
    const Vec3 wiWorld = bsdf.toWorld(ds->w);
    ray = Ray{offsetPoint(vertex.p, vertex.ng, wiWorld), wiWorld};
    if (media) medium = where.leaving(scene, vertex, wiWorld);

    // Russian roulette on the lanes' total throughput (every lane divided by the same q).
    if (depth + 1 >= rrDepth_) {
      const float q = std::min(1.0f, m / magnitude0);
      if (rng.uniform() >= q) break;
      for (int j = 0; j < lanes.n; ++j) lanes.beta[j] /= q;
    }
  }
  return L;
}

}  // namespace kasha
