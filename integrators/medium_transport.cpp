#include "integrators/medium_transport.h"

#include <algorithm>
#include <cmath>

namespace kasha {
namespace {

// Index-matched boundaries a ray may cross before it counts as lost in a numerical loop (a ray
// grazing a boundary's edge): it then carries nothing (absorbed), which only removes energy.
constexpr int kMaxCrossings = 256;
// The first dimension of the free flights' region (docs/sampler.md).
constexpr uint32_t kFreeFlightDimensions = 1u << 28;

// σ·d where σ = 0 contributes nothing even over an infinite distance.
float opticalDepth(float sigma, float distance) { return sigma > 0.0f ? sigma * distance : 0.0f; }

}  // namespace

void LaneRatios::reset(int lanes) {
  n = lanes;
  std::fill(r, r + n, 1.0f);
}

float LaneRatios::misWeight() const {
  float s = 0.0f;
  for (int k = 0; k < n; ++k) s += r[k];
  return float(n) / s;
}

FreeFlight traceFreeFlight(const Scene& scene, Ray ray, int medium, std::span<const float> lambda, float u,
                           TransportMode mode, RayCounter& counter) {
  FreeFlight f;
  const size_t n = lambda.size();
  std::fill(f.weight, f.weight + n, 1.0f);
  std::fill(f.ratio, f.ratio + n, 1.0f);
  if (!scene.hasMedia()) {
    f.hit = scene.accel->intersect(ray);
    ++counter.closest;
    return f;
  }
  // A camera path's flight in a fluorescent medium is drawn from the one-sample mixture of the
  // analog density (rate σ_t) and a source-seeking one (rate σ̄ = σ_t + A_fl, A_fl the fluorescent
  // source rate at λ_o), each with probability ½ (docs/media-scenes.md, "Path tracing in
  // fluorescent media"; Veach 1997 §9.2.4, one-sample model with the balance heuristic). Its
  // density, and its lanes': ½·σ_t·e^{−τ} + ½·σ̄·e^{−τ̄} at a collision, ½·e^{−τ} + ½·e^{−τ̄} past it.
  const bool mixture = mode == TransportMode::Radiance &&
                       std::any_of(scene.media.begin(), scene.media.end(), [](const auto& m) { return m->fluoresces(); });
  const bool seek = mixture && u >= 0.5f;
  if (mixture) u = seek ? 2.0f * u - 1.0f : 2.0f * u;
  const float target = -std::log1p(-std::min(u, 0x1.fffffep-1f));  // the drawn component's optical depth at λ_0
  float tau[kMaxLanes] = {};      // optical depth so far per lane
  float tauSeek[kMaxLanes] = {};  // the same with σ_t + A_fl
  const auto sourceRate = [&](int m, float l) {
    return mixture ? scene.mediumScattering[size_t(m)]->fluorescentWeight(TransportMode::Radiance, l) : 0.0f;
  };
  // Lane k's density over e^{−τ_0}, with rates sigma (σ_t) and seekRate (σ_t + A_fl) at the end
  // point: 1 and 1 for a flight past it.
  const auto density = [&](size_t k, float sigma, float seekRate) {
    const float analog = sigma * std::exp(tau[0] - tau[k]);
    return mixture ? 0.5f * (analog + seekRate * std::exp(tau[0] - tauSeek[k])) : analog;
  };
  for (int crossing = 0; crossing <= kMaxCrossings; ++crossing) {
    const std::optional<Hit> hit = scene.accel->intersect(ray);
    ++counter.closest;
    const float length = hit ? hit->t : kInf;
    if (medium >= 0) {
      const Medium& m = *scene.media[size_t(medium)];
      float sigma[kMaxLanes], seekRate[kMaxLanes];
      for (size_t k = 0; k < n; ++k) {
        sigma[k] = m.sigmaT(lambda[k]);
        seekRate[k] = sigma[k] + sourceRate(medium, lambda[k]);
      }
      const float rate0 = seek ? seekRate[0] : sigma[0], drawn = seek ? tauSeek[0] : tau[0];
      if (rate0 > 0.0f && target - drawn < rate0 * length) {
        // A collision: lane k's T_k = e^{−τ_k}; its weight T_k/p_0 and ratio p_k/p_0.
        const float t = (target - drawn) / rate0;
        for (size_t k = 0; k < n; ++k) {
          tau[k] += opticalDepth(sigma[k], t);
          tauSeek[k] += opticalDepth(seekRate[k], t);
        }
        const float p0 = density(0, sigma[0], seekRate[0]);
        for (size_t k = 0; k < n; ++k) {
          f.weight[k] = std::exp(tau[0] - tau[k]) / p0;
          f.ratio[k] = density(k, sigma[k], seekRate[k]) / p0;
        }
        f.collided = true;
        f.p = ray.o + t * ray.d;
        f.medium = medium;
        return f;
      }
      for (size_t k = 0; k < n; ++k) {
        tau[k] += opticalDepth(sigma[k], length);
        tauSeek[k] += opticalDepth(seekRate[k], length);
      }
    }
    if (!hit || !scene.shapes[hit->shape].isMediumBoundary()) {
      // Passed every medium on the way: lane k's probability P_k; the weight T_k/P_0, the ratio P_k/P_0.
      const float p0 = density(0, 1.0f, 1.0f);
      for (size_t k = 0; k < n; ++k) {
        f.weight[k] = std::exp(tau[0] - tau[k]) / p0;
        f.ratio[k] = density(k, 1.0f, 1.0f) / p0;
      }
      f.hit = hit;
      f.medium = medium;
      return f;
    }
    medium = scene.mediumBeyond(*hit, ray.d, medium);
    ray.o = offsetPoint(hit->p, hit->ng, ray.d);
  }
  std::fill(f.weight, f.weight + n, 0.0f);  // lost between boundaries: absorbed
  f.medium = medium;
  return f;
}

bool segmentTransmittance(const Scene& scene, Vec3 origin, const Vec3& d, float tMax, int medium,
                          std::span<const float> lambda, float* tr, RayCounter& counter) {
  const size_t n = lambda.size();
  if (!scene.hasMedia()) {
    ++counter.shadow;
    if (scene.accel->occluded(origin, d, tMax)) return false;
    std::fill(tr, tr + n, 1.0f);
    return true;
  }
  float tau[kMaxLanes] = {};
  for (int crossing = 0; crossing <= kMaxCrossings; ++crossing) {
    ++counter.closest;
    const std::optional<Hit> hit = scene.accel->intersect(Ray{origin, d, tMax});
    if (hit && !scene.shapes[hit->shape].isMediumBoundary()) return false;
    const float length = hit ? hit->t : tMax;
    if (medium >= 0)
      for (size_t k = 0; k < n; ++k) tau[k] += opticalDepth(scene.media[size_t(medium)]->sigmaT(lambda[k]), length);
    if (!hit) {
      for (size_t k = 0; k < n; ++k) tr[k] = std::exp(-tau[k]);
      return true;
    }
    medium = scene.mediumBeyond(*hit, d, medium);
    origin = offsetPoint(hit->p, hit->ng, d);
    tMax -= hit->t;
  }
  return false;
}

bool lightTransmittance(const Scene& scene, const Hit& hit, VertexMedium where, const LightSample& ls,
                        std::span<const float> lambda, float* tr, RayCounter& counter) {
  const Vec3 origin = offsetPoint(hit.p, hit.ng, ls.wi);
  const float tMax = std::isinf(ls.dist) ? kInf : ls.dist * (1.0f - 1e-4f) - rayEpsilon(hit.p);
  return segmentTransmittance(scene, origin, ls.wi, tMax, where.leaving(scene, hit, ls.wi), lambda, tr, counter);
}

float freeFlightUniform(Sampler& rng, uint32_t firstDimension, int depth) {
  rng.setDimension(kFreeFlightDimensions + firstDimension + uint32_t(depth));
  const float u = rng.uniform();
  rng.startVertex(firstDimension, depth);
  return u;
}

}  // namespace kasha
