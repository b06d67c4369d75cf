#include "integrators/light_subpath_lanes.h"

#include <algorithm>
#include <cmath>

namespace kasha {

float LightLanes::sum() const {
  float s = 0.0f;
  for (int k = 0; k < n; ++k) s += beta[k];
  return s;
}

LightStartLanes startLightLanes(const Scene& scene, const WavelengthDensity& density, int n, float uLambda, float uLight,
                                Vec2 uPos, Vec2 uDir) {
  LightStartLanes s;
  float* lambda = s.lanes.lambda;
  float pdf[kMaxLanes];
  for (int j = 0; j < n; ++j) {
    const WavelengthSample ws = density.sample(laneStratum(uLambda, j, n));
    lambda[j] = ws.lambda;
    pdf[j] = ws.pdf;
  }
  const auto [li, pSelect] = selectLaneLight(scene, {lambda, size_t(n)}, uLight);
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

std::optional<Vec3> scatterLightLanes(const Bsdf& bsdf, const Vec3& wi, const LaneEvent& e, LightLanes& lanes,
                                      bool roulette, float beta0, Sampler& rng) {
  const float lambdaIn0 = e.lobe == SpectralLobe::Elastic ? e.lambda[0] : lanes.lambda[0];
  const std::optional<DirectionSample> ds =
      bsdf.sampleDirection(TransportMode::Importance, wi, e.lobe, lambdaIn0, e.lambda[0], rng.uniform2());
  if (!ds || ds->pdf <= 0.0f) return std::nullopt;
  const std::span<const float> known(lanes.lambda, size_t(lanes.n));
  float next[kMaxLanes];
  for (int k = 0; k < e.n; ++k)
    next[k] = laneWeight(bsdf, TransportMode::Importance, known, lanes.beta, e, k, ds->w, wi) * bsdf.cosineFactor(ds->w) / ds->pdf;
  lanes.n = e.n;
  std::copy(next, next + e.n, lanes.beta);
  std::copy(e.lambda, e.lambda + e.n, lanes.lambda);
  const float m = lanes.sum();
  if (!(m > 0.0f)) return std::nullopt;
  if (roulette) {
    const float q = std::min(1.0f, m / beta0);
    if (rng.uniform() >= q) return std::nullopt;
    for (int k = 0; k < lanes.n; ++k) lanes.beta[k] /= q;
  }
  return bsdf.toWorld(ds->w);
}

}  // namespace kasha
