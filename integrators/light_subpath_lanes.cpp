#include "integrators/light_subpath_lanes.h"

#include <algorithm>
#include <cmath>

#include "integrators/lane_light_choice.h"

namespace kasha {

LightStartLanes startLightLanes(const Scene& scene, const WavelengthDensity& density, int n, float uLambda, float uLight,
                                Vec2 uPos, Vec2 uDir) {
  LightStartLanes s;
  const SampledLanes sampled = sampleLanes(density, uLambda, n);
  float* lambda = s.lanes.lambda;
  std::copy(sampled.lambda, sampled.lambda + n, lambda);
  const float* pdf = sampled.pdf;
  thread_local LaneLightTable lights;
  lights.reset(scene, sampled.wavelengths());
  const auto [li, pSelect] = lights.select(uLight);
  if (!(pSelect > 0.0f)) return s;
  s.light = scene.lights[li].get();
  s.lightIndex = li;
  const std::optional<EmissionSample> es = s.light->sampleEmission(lambda[0], uPos, uDir);
  if (!es || es->pdfPos <= 0.0f || es->pdfDir <= 0.0f) return s;
  s.es = *es;
  for (int j = 0; j < n; ++j) {
    const float Le = j == 0 ? es->Le : s.light->emitted(*es, lambda[j]);
    s.start[j] = pdf[j] > 0.0f ? 1.0f / (float(n) * pdf[j] * pSelect) : 0.0f;
    s.lanes.beta[j] = s.start[j] > 0.0f ? Le * s.start[j] * es->cosOrigin / (es->pdfPos * es->pdfDir) : 0.0f;
  }
  s.lanes.n = n;
  return s;
}

LightOrigin lightOrigin(const Scene& scene, const LightStartLanes& start) {
  LightOrigin o;
  o.hit.p = start.es.p;
  o.hit.ng = start.es.n;
  const int shape = scene.emittingShape(*start.light, start.es);
  if (shape >= 0) o.hit.shape = uint32_t(shape);
  o.where = VertexMedium{scene.lightMedium[start.lightIndex], shape >= 0};
  return o;
}

std::optional<LightSubpathVertex> nextLightVertex(const Scene& scene, const Ray& ray, int medium, LightLanes& lanes,
                                                  LaneRatios& ratios, Sampler& rng, uint32_t firstDimension, int depth,
                                                  RayCounter& counter) {
  rng.startVertex(firstDimension, depth - 1);
  const bool media = scene.hasMedia();
  const float uFlight = media ? freeFlightUniform(rng, firstDimension, depth - 1) : 0.0f;
  const std::span<const float> lambda(lanes.lambda, size_t(lanes.n));
  const FreeFlight flight = traceFreeFlight(scene, ray, medium, lambda, uFlight, TransportMode::Importance, counter);
  float mis = 1.0f;
  if (media) {
    for (int k = 0; k < lanes.n; ++k) {
      lanes.beta[k] *= flight.weight[k];
      ratios.r[k] *= flight.ratio[k];
    }
    mis = ratios.misWeight();
  }
  if (!flight.hit && !flight.collided) return std::nullopt;
  Hit vertex;
  if (flight.hit) vertex = *flight.hit;
  else vertex.p = flight.p, vertex.ng = Vec3(0.0f);
  const Bsdf bsdf = flight.hit ? scene.bsdf(vertex, lambda) : scene.mediumBsdf(flight.medium, flight.p);
  return LightSubpathVertex{vertex, VertexMedium{flight.medium, flight.hit.has_value()}, bsdf, mis};
}

std::optional<Vec3> scatterLightLanes(const Bsdf& bsdf, const Vec3& wi, const LaneEvent& e, LightLanes& lanes,
                                      bool roulette, float beta0, Sampler& rng) {
  const float lambdaIn0 = e.lobe == SpectralLobe::Elastic ? e.lambda[0] : lanes.lambda[0];
  const std::optional<DirectionSample> ds =
      bsdf.sampleDirection({TransportMode::Importance, e.lobe, lambdaIn0, e.lambda[0]}, wi, rng.uniform2());
  if (!ds || ds->pdf <= 0.0f) return std::nullopt;
  const std::span<const float> known(lanes.lambda, size_t(lanes.n));
  float next[kMaxLanes];
  for (int k = 0; k < e.n; ++k)
    next[k] = laneWeight(bsdf, TransportMode::Importance, known, lanes.beta, e, k, ds->w, wi) * bsdf.cosineFactor(ds->w) / ds->pdf;
  lanes.n = e.n;
  std::copy(next, next + e.n, lanes.beta);
  std::copy(e.lambda, e.lambda + e.n, lanes.lambda);
  const float m = magnitude(lanes);
  if (!(m > 0.0f)) return std::nullopt;
  if (roulette) {
    const float q = std::min(1.0f, m / beta0);
    if (rng.uniform() >= q) return std::nullopt;
    for (int k = 0; k < lanes.n; ++k) lanes.beta[k] /= q;
  }
  return bsdf.toWorld(ds->w);
}

}  // namespace kasha
