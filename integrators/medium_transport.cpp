#include "integrators/medium_transport.h"

#include <algorithm>
#include <bit>
#include <cmath>

#include "core/rng.h"

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

namespace {

// The numbers of a flight's tracking after its first (u, stratified): a PCG32 stream seeded by a
// hash of the ray and u, so that it is a function of the path's own random numbers and needs no
// sampler dimensions of its own.
Rng trackingStream(const Ray& ray, float u) {
  const auto bits = [](float x) { return uint64_t(std::bit_cast<uint32_t>(x)); };
  const uint64_t a = mixBits(bits(ray.o.x) | bits(ray.o.y) << 32) ^ mixBits(bits(ray.o.z) | bits(u) << 32);
  const uint64_t b = mixBits(bits(ray.d.x) | bits(ray.d.y) << 32) ^ bits(ray.d.z);
  return Rng(a, b);
}

}  // namespace

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
  // Tentative collisions at the majorant σ̄(λ_0) = max d·σ_t(λ_0) (media.md §4; in a homogeneous
  // medium σ_t itself, and every one is real): the next one where the majorant's optical depth at
  // λ_0 since the last reaches `target`.
  float target = -std::log1p(-u), depth0 = 0.0f;
  float majorantDepth[kMaxLanes] = {};  // τ̄_k over the whole flight, for T̄_k = exp(−τ̄_k)
  float nullRatio[kMaxLanes];           // Π over null collisions of σ_n,k/σ_n,0
  std::fill(nullRatio, nullRatio + n, 1.0f);
  std::optional<Rng> stream;  // created at the first null collision
  for (int crossing = 0; crossing <= kMaxCrossings; ++crossing) {
    const std::optional<Hit> hit = scene.accel->intersect(ray);
    ++counter.closest;
    const float length = hit ? hit->t : kInf;
    if (medium >= 0) {
      const Medium& m = *scene.media[size_t(medium)];
      float sigma[kMaxLanes];  // σ_t(λ_k) of the medium without its density
      for (size_t k = 0; k < n; ++k) sigma[k] = m.sigmaT(lambda[k]);
      const float dMax = m.maxDensity(), majorant0 = opticalDepth(sigma[0], dMax);
      float t = 0.0f;  // along this segment
      while (majorant0 > 0.0f && target - depth0 < majorant0 * (length - t)) {
        const float dt = (target - depth0) / majorant0;
        t += dt;
        for (size_t k = 0; k < n; ++k) majorantDepth[k] += opticalDepth(sigma[k] * dMax, dt);
        depth0 = 0.0f;
        const Vec3 x = ray.o + t * ray.d;
        // Real with probability σ_t(x, λ_0)/σ̄(λ_0) = d(x)/max d (always in a homogeneous medium).
        if (m.heterogeneous()) {
          if (!stream) stream = trackingStream(ray, u);
          if (!(stream->uniform() * dMax < m.density(x))) {
            // Null: lane k's σ_n,k = (max d − d(x))·σ_t(λ_k), so σ_n,k/σ_n,0 = σ_t(λ_k)/σ_t(λ_0).
            for (size_t k = 1; k < n; ++k) nullRatio[k] *= sigma[k] / sigma[0];
            target = -std::log1p(-stream->uniform());
            continue;
          }
        }
        // A collision: T̄_k·(null factors)/(T̄_0·σ_t(λ_0)), with σ_t without the density d(x), which
        // the collision's kernel (the medium's σ(λ) without it) would multiply: it cancels.
        for (size_t k = 0; k < n; ++k) {
          const float rel = nullRatio[k] * std::exp(majorantDepth[0] - majorantDepth[k]);
          f.weight[k] = rel / sigma[0];
          f.ratio[k] = rel * sigma[k] / sigma[0];
        }
        f.collided = true;
        f.p = x;
        f.medium = medium;
        return f;
      }
      const float rest = length - t;
      depth0 += opticalDepth(majorant0, rest);
      for (size_t k = 0; k < n; ++k) majorantDepth[k] += opticalDepth(sigma[k] * dMax, rest);
    }
    if (!hit || !scene.shapes[hit->shape].isMediumBoundary()) {
      // Passed every medium on the way: P_k = T̄_k·(null factors), the weight and the ratio are P_k/P_0.
      for (size_t k = 0; k < n; ++k) f.weight[k] = f.ratio[k] = nullRatio[k] * std::exp(majorantDepth[0] - majorantDepth[k]);
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
  float tau[kMaxLanes] = {};  // homogeneous segments' optical depth
  float ratio[kMaxLanes];     // heterogeneous segments' ratio-tracking estimates
  std::fill(ratio, ratio + n, 1.0f);
  std::optional<Rng> stream;
  for (int crossing = 0; crossing <= kMaxCrossings; ++crossing) {
    ++counter.closest;
    const std::optional<Hit> hit = scene.accel->intersect(Ray{origin, d, tMax});
    if (hit && !scene.shapes[hit->shape].isMediumBoundary()) return false;
    const float length = hit ? hit->t : tMax;
    if (medium >= 0) {
      const Medium& m = *scene.media[size_t(medium)];
      if (!m.heterogeneous()) {
        for (size_t k = 0; k < n; ++k) tau[k] += opticalDepth(m.sigmaT(lambda[k]), length);
      } else {
        // Ratio tracking (Novák et al. 2014) with one majorant for every lane, σ̄ = max d·max_k σ_t(λ_k):
        // T_k is the expectation of Π (1 − d(x_i)·σ_t(λ_k)/σ̄) over the tentative collisions x_i.
        float sigma[kMaxLanes], sigmaMax = 0.0f;
        for (size_t k = 0; k < n; ++k) sigmaMax = std::max(sigmaMax, sigma[k] = m.sigmaT(lambda[k]));
        const float majorant = sigmaMax * m.maxDensity();
        if (!stream) stream = trackingStream(Ray{origin, d}, 0.5f);
        for (float t = 0.0f; majorant > 0.0f && std::isfinite(length);) {
          t -= std::log1p(-stream->uniform()) / majorant;
          if (!(t < length)) break;
          const float dx = m.density(origin + t * d);
          for (size_t k = 0; k < n; ++k) ratio[k] *= std::max(0.0f, 1.0f - dx * sigma[k] / majorant);
        }
        if (!std::isfinite(length) && majorant > 0.0f) std::fill(ratio, ratio + n, 0.0f);
      }
    }
    if (!hit) {
      for (size_t k = 0; k < n; ++k) tr[k] = ratio[k] * std::exp(-tau[k]);
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
