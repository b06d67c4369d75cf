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

// A ray crossing an index-matched boundary at `hit` goes on from offsetPoint(hit.p, hit.ng, d), ε
// off the surface along its normal: ε/|cos θ| along d (for a locally flat boundary) of the medium
// beyond lies behind the new origin. Its optical depth is part of the path: skipping it lost a
// layer ε thick of every medium entered (a fluorescent slab 0.01 thick seen at cos θ = 0.6 came out
// 0.3% too dark; validation.md §5a). |cos θ| is kept above 10⁻³: a grazing ray adds at most 1000·ε.
float crossingGap(const Hit& hit, const Vec3& d) {
  return rayEpsilon(hit.p) / std::max(std::abs(glm::dot(hit.ng, d)), 1e-3f);
}

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
                           RayCounter& counter) {
  FreeFlight f;
  const size_t n = lambda.size();
  std::fill(f.weight, f.weight + n, 1.0f);
  std::fill(f.ratio, f.ratio + n, 1.0f);
  if (!scene.hasMedia()) {
    f.hit = scene.accel->intersect(ray);
    ++counter.closest;
    return f;
  }
  const float target = -std::log1p(-u);  // the optical depth at λ_0 where the flight ends
  float tau[kMaxLanes] = {};              // optical depth so far per lane
  float gap = 0.0f;                       // of the medium behind ray.o (crossingGap)
  for (int crossing = 0; crossing <= kMaxCrossings; ++crossing) {
    const std::optional<Hit> hit = scene.accel->intersect(ray);
    ++counter.closest;
    const float length = gap + (hit ? hit->t : kInf);  // in this medium, from the boundary
    if (medium >= 0) {
      const Medium& m = *scene.media[size_t(medium)];
      const float sigma0 = m.sigmaT(lambda[0]);
      if (sigma0 > 0.0f && target - tau[0] < sigma0 * length) {
        // A collision: lane k's T_k = exp(−τ_k), p_0 = σ_t(λ_0)·exp(−τ_0), p_k = σ_t(λ_k)·exp(−τ_k).
        const float t = (target - tau[0]) / sigma0;  // from the boundary
        for (size_t k = 1; k < n; ++k) tau[k] += opticalDepth(m.sigmaT(lambda[k]), t);
        tau[0] = target;
        for (size_t k = 0; k < n; ++k) {
          const float rel = std::exp(tau[0] - tau[k]);
          f.weight[k] = rel / sigma0;
          f.ratio[k] = (k == 0 ? sigma0 : m.sigmaT(lambda[k])) * rel / sigma0;
        }
        f.collided = true;
        f.p = ray.o + std::max(t - gap, 0.0f) * ray.d;
        f.medium = medium;
        return f;
      }
      for (size_t k = 0; k < n; ++k) tau[k] += opticalDepth(k == 0 ? sigma0 : m.sigmaT(lambda[k]), length);
    }
    if (!hit || !scene.shapes[hit->shape].isMediumBoundary()) {
      // Passed every medium on the way: P_k = exp(−τ_k), the weight and the ratio are P_k/P_0.
      for (size_t k = 0; k < n; ++k) f.weight[k] = f.ratio[k] = std::exp(tau[0] - tau[k]);
      f.hit = hit;
      f.medium = medium;
      return f;
    }
    medium = scene.mediumBeyond(*hit, ray.d, medium);
    ray.o = offsetPoint(hit->p, hit->ng, ray.d);
    gap = crossingGap(*hit, ray.d);
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
  float gap = 0.0f;  // of the medium behind origin (crossingGap); tMax is counted from the boundary
  for (int crossing = 0; crossing <= kMaxCrossings; ++crossing) {
    ++counter.closest;
    const std::optional<Hit> hit = scene.accel->intersect(Ray{origin, d, std::max(tMax - gap, 0.0f)});
    if (hit && !scene.shapes[hit->shape].isMediumBoundary()) return false;
    const float length = hit ? gap + hit->t : tMax;
    if (medium >= 0)
      for (size_t k = 0; k < n; ++k) tau[k] += opticalDepth(scene.media[size_t(medium)]->sigmaT(lambda[k]), length);
    if (!hit) {
      for (size_t k = 0; k < n; ++k) tr[k] = std::exp(-tau[k]);
      return true;
    }
    medium = scene.mediumBeyond(*hit, d, medium);
    origin = offsetPoint(hit->p, hit->ng, d);
    tMax -= length;
    gap = crossingGap(*hit, d);
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
