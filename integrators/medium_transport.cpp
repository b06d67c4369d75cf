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

// A ray crossing an index-matched boundary at `hit` goes on from offsetPoint(hit.p, hit.ng, d), ε
// off the surface along its normal: ε/|cos θ| along d (for a locally flat boundary) of the medium
// beyond lies behind the new origin. Its optical depth is part of the path: skipping it lost a
// layer ε thick of every medium entered (a fluorescent slab 0.01 thick seen at cos θ = 0.6 came out
// 0.3% too dark; validation.md §5a). |cos θ| is kept above 10⁻³: a grazing ray adds at most 1000·ε.
float crossingGap(const Hit& hit, const Vec3& d) {
  return rayEpsilon(hit.p) / std::max(std::abs(glm::dot(hit.ng, d)), 1e-3f);
}

// The numbers of a flight's tracking after its first (u, stratified): a PCG32 stream seeded by a
// hash of the ray and u, so that it is a function of the path's own random numbers and needs no
// sampler dimensions of its own.
Rng trackingStream(const Ray& ray, float u) {
  const auto bits = [](float x) { return uint64_t(std::bit_cast<uint32_t>(x)); };
  const uint64_t a = mixBits(bits(ray.o.x) | bits(ray.o.y) << 32) ^ mixBits(bits(ray.o.z) | bits(u) << 32);
  const uint64_t b = mixBits(bits(ray.d.x) | bits(ray.d.y) << 32) ^ bits(ray.d.z);
  return Rng(a, b);
}

// Points of the midpoint rule over a heterogeneous portion (densityIntegral).
constexpr int kDepthPoints = 16;

// ∫ d(x) dx over [t0, t1] of a heterogeneous portion of `ray` (t counted from the boundary, which
// lies `gap` behind ray.o), by the midpoint rule with kDepthPoints points: times σ_t(λ), an estimate
// of the portion's optical depth. A deterministic function of the segment, as the bidirectional
// weights need the free flights' densities to be (media.md §5): any such function keeps them a
// partition of unity, while the estimates themselves use delta and ratio tracking.
float densityIntegral(const Medium& m, const Ray& ray, float gap, float t0, float t1) {
  if (!(t1 > t0)) return 0.0f;
  const float dt = (t1 - t0) / float(kDepthPoints);
  float sum = 0.0f;
  for (int i = 0; i < kDepthPoints; ++i)
    sum += m.density(ray.o + std::max(t0 + (float(i) + 0.5f) * dt - gap, 0.0f) * ray.d);
  return sum * dt;
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

FreeFlight traceFreeFlightThroughMedia(const Scene& scene, Ray ray, int medium, std::span<const float> lambda, float u,
                                       TransportMode mode, RayCounter& counter, bool estimateDepth) {
  FreeFlight f;
  const size_t n = lambda.size();
  // A camera path's flight, in a scene with a fluorescent medium, is drawn from the one-sample
  // mixture of the analog density (rate σ_t) and a source-seeking one (rate σ_t + A_fl, A_fl the
  // fluorescent source rate at λ_o of media.md eq. 5), each with probability ½ (media.md eq. 6b;
  // Veach 1997 §9.2.4): a medium that fluoresces at λ_o without absorbing it (a Stokes shift)
  // would otherwise never be collided with at λ_o. Fluorescent media are homogeneous (media.md §4),
  // so in a heterogeneous medium both components are the same delta tracking against the majorant
  // σ̄(λ) = max d·σ_t(λ) (media.md eq. 8).
  const bool fluorescent = scene.hasFluorescentMedia();
  const bool mixture = mode == TransportMode::Radiance && fluorescent;
  const bool seek = mixture && u >= 0.5f;
  if (mixture) u = seek ? 2.0f * u - 1.0f : 2.0f * u;
  // The drawn component's optical depth at λ_0 left until its next (tentative) collision.
  float remaining = -std::log1p(-std::min(u, 0x1.fffffep-1f));
  // Per lane, over the flight: optical depth of the analog component (homogeneous σ_t·d, and the
  // majorant's σ̄·d in heterogeneous media) and of the seeking one, and Π σ_n,k/σ_n,0 over null
  // collisions.
  float tau[kMaxLanes] = {}, tauSeek[kMaxLanes] = {}, nullRatio[kMaxLanes];
  std::fill(nullRatio, nullRatio + n, 1.0f);
  // Lane k's density of the flight's end over exp(−τ_0), with end factors `analog` and `seeking`
  // (the rates at a collision, 1 past the media): the value, times nullRatio_k, is p_k/exp(−τ_0).
  const auto density = [&](size_t k, float analog, float seeking) {
    return nullRatio[k] * freeFlightDensity(mixture, {tau[k] - tau[0], tauSeek[k] - tau[0]}, analog, seeking);
  };
  // With estimateDepth, FreeFlight::depth counts heterogeneous portions by their estimated optical
  // depth (densityIntegral) in place of the majorant's: what tau[0] and tauSeek[0] hold of
  // majorants, and the estimates.
  float majorantDepth = 0.0f, majorantSeekDepth = 0.0f, estimatedDepth = 0.0f, estimatedSeekDepth = 0.0f;
  bool inMedia = false;  // whether the flight entered a medium so far
  bool crossed = false;  // whether it crossed an index-matched boundary so far
  const auto depthOfFlight = [&] {
    return SegmentDepth{tau[0] - majorantDepth + estimatedDepth, tauSeek[0] - majorantSeekDepth + estimatedSeekDepth,
                        inMedia, crossed};
  };
  std::optional<Rng> stream;  // created at the first null collision
  float gap = 0.0f;           // of the medium behind ray.o (crossingGap)
  for (int crossing = 0; crossing <= kMaxCrossings; ++crossing) {
    const std::optional<Hit> hit = scene.accel->intersect(ray);
    ++counter.closest;
    const float length = gap + (hit ? hit->t : kInf);  // in this medium, from the boundary
    if (medium >= 0) {
      inMedia = true;
      const Medium& m = *scene.media[size_t(medium)];
      const float dMax = m.maxDensity();
      float sigma[kMaxLanes], seekRate[kMaxLanes];  // σ_t (times max d: the majorant) and σ_t + A_fl
      for (size_t k = 0; k < n; ++k) {
        sigma[k] = m.sigmaT(lambda[k]);
        // Tracked on light paths too: their flights are also camera paths' (FreeFlight::depth, BDPT's MIS).
        seekRate[k] = sigma[k] + (fluorescent ? scene.mediumScattering[size_t(medium)]->fluorescentWeight(
                                                    TransportMode::Radiance, lambda[k])
                                              : 0.0f);
        sigma[k] *= dMax, seekRate[k] *= dMax;
      }
      const float rate0 = seek ? seekRate[0] : sigma[0];
      // Beyond its density's extent a heterogeneous medium is empty: the majorant is 0 there.
      const float active = std::min(length, gap + m.densityExtent(ray.o, ray.d));
      const bool estimate = estimateDepth && m.heterogeneous();
      const float tauAtBoundary = tau[0], tauSeekAtBoundary = tauSeek[0];
      // The portion [0, end] of this medium's segment into FreeFlight::depth's estimate.
      const auto estimatePortion = [&](float end) {
        const float integral = densityIntegral(m, ray, gap, 0.0f, end);
        majorantDepth += tau[0] - tauAtBoundary, majorantSeekDepth += tauSeek[0] - tauSeekAtBoundary;
        estimatedDepth += sigma[0] / dMax * integral, estimatedSeekDepth += seekRate[0] / dMax * integral;
      };
      float t = 0.0f;  // along this segment, from the boundary
      while (rate0 > 0.0f && remaining < rate0 * (active - t)) {
        const float dt = remaining / rate0;
        t += dt;
        for (size_t k = 0; k < n; ++k) {
          tau[k] += opticalDepth(sigma[k], dt);
          tauSeek[k] += opticalDepth(seekRate[k], dt);
        }
        const Vec3 x = ray.o + std::max(t - gap, 0.0f) * ray.d;
        // Real with probability σ_t(x, λ_0)/σ̄(λ_0) = d(x)/max d (always in a homogeneous medium).
        if (m.heterogeneous()) {
          if (!stream) stream = trackingStream(ray, u);
          if (!(stream->uniform() * dMax < m.density(x))) {
            // Null: σ_n,k = (max d − d(x))·σ_t(λ_k), so σ_n,k/σ_n,0 = σ_t(λ_k)/σ_t(λ_0).
            for (size_t k = 1; k < n; ++k) nullRatio[k] *= sigma[k] / sigma[0];
            remaining = -std::log1p(-stream->uniform());
            continue;
          }
        }
        // A collision: weight T_k/p_0 and ratio p_k/p_0, with the rates without the density d(x),
        // which the collision's kernel (the medium's σ(λ) without it) would multiply: it cancels.
        const float p0 = density(0, sigma[0] / dMax, seekRate[0] / dMax);
        for (size_t k = 0; k < n; ++k) {
          f.weight[k] = nullRatio[k] * std::exp(tau[0] - tau[k]) / p0;
          f.ratio[k] = density(k, sigma[k] / dMax, seekRate[k] / dMax) / p0;
        }
        f.collided = true;
        if (estimate) estimatePortion(t);
        f.depth = depthOfFlight();
        f.p = x;
        f.medium = medium;
        return f;
      }
      const float rest = active - t;
      if (rate0 > 0.0f) remaining -= rate0 * rest;
      for (size_t k = 0; k < n; ++k) {
        tau[k] += opticalDepth(sigma[k], rest);
        tauSeek[k] += opticalDepth(seekRate[k], rest);
      }
      if (estimate) estimatePortion(active);
    }
    if (!hit || !scene.shapes[hit->shape].isMediumBoundary()) {
      // Passed every medium on the way: lane k's probability P_k; the weight T_k/P_0, the ratio P_k/P_0.
      const float p0 = density(0, 1.0f, 1.0f);
      for (size_t k = 0; k < n; ++k) {
        f.weight[k] = nullRatio[k] * std::exp(tau[0] - tau[k]) / p0;
        f.ratio[k] = density(k, 1.0f, 1.0f) / p0;
      }
      f.hit = hit;
      f.medium = medium;
      f.depth = depthOfFlight();
      return f;
    }
    medium = scene.mediumBeyond(*hit, ray.d, medium);
    ray.o = offsetPoint(hit->p, hit->ng, ray.d);
    gap = crossingGap(*hit, ray.d);
    crossed = true;
  }
  std::fill(f.weight, f.weight + n, 0.0f);  // lost between boundaries: absorbed
  std::fill(f.ratio, f.ratio + n, 1.0f);
  f.medium = medium;
  // Absorbed at every wavelength, as through a medium: the lanes of a caller that flew at lane 0's
  // alone end with it (the bidirectional engine's, docs/media.md §5).
  f.depth = depthOfFlight();
  f.depth.inMedia = true;
  return f;
}

SegmentDepth depthThrough(const Scene& scene, int medium, float lambda, float length) {
  const float sigma = scene.media[size_t(medium)]->sigmaT(lambda);
  const float seekRate =
      sigma + scene.mediumScattering[size_t(medium)]->fluorescentWeight(TransportMode::Radiance, lambda);
  return {opticalDepth(sigma, length), opticalDepth(seekRate, length), true, false};
}

bool segmentTransmittanceThroughMedia(const Scene& scene, Vec3 origin, const Vec3& d, float tMax, int medium,
                                      std::span<const float> lambda, float* tr, RayCounter& counter, SegmentDepth* depths) {
  const size_t n = lambda.size();
  float tau[kMaxLanes] = {};  // homogeneous segments' optical depth
  if (depths) std::fill(depths, depths + n, SegmentDepth{});
  float ratio[kMaxLanes];     // heterogeneous segments' ratio-tracking estimates
  std::fill(ratio, ratio + n, 1.0f);
  std::optional<Rng> stream;
  float gap = 0.0f;  // of the medium behind origin (crossingGap); tMax is counted from the boundary
  for (int crossing = 0; crossing <= kMaxCrossings; ++crossing) {
    ++counter.closest;
    const std::optional<Hit> hit = scene.accel->intersect(Ray{origin, d, std::max(tMax - gap, 0.0f)});
    if (hit && !scene.shapes[hit->shape].isMediumBoundary()) return false;
    const float length = hit ? gap + hit->t : tMax;
    if (medium >= 0) {
      for (size_t k = 0; depths && k < n; ++k) depths[k].inMedia = true;
      const Medium& m = *scene.media[size_t(medium)];
      // The optical depths for `depths`: exact in a homogeneous medium, estimated in a heterogeneous
      // one (densityIntegral); its seeking rate is σ_t + A_fl.
      const float integral = depths && m.heterogeneous()
                                 ? densityIntegral(m, Ray{origin, d}, gap, 0.0f, std::min(length, gap + m.densityExtent(origin, d)))
                                 : length;
      for (size_t k = 0; depths && k < n; ++k) {
        const SegmentDepth part = depthThrough(scene, medium, lambda[k], integral);
        depths[k].analog += part.analog;
        depths[k].seeking += part.seeking;
      }
      if (!m.heterogeneous()) {
        for (size_t k = 0; k < n; ++k) tau[k] += opticalDepth(m.sigmaT(lambda[k]), length);
      } else {
        // Ratio tracking (Novák et al. 2014) with one majorant for every lane, σ̄ = max d·max_k σ_t(λ_k):
        // T_k is the expectation of Π (1 − d(x_i)·σ_t(λ_k)/σ̄) over the tentative collisions x_i.
        float sigma[kMaxLanes], sigmaMax = 0.0f;
        for (size_t k = 0; k < n; ++k) sigmaMax = std::max(sigmaMax, sigma[k] = m.sigmaT(lambda[k]));
        const float majorant = sigmaMax * m.maxDensity();
        if (!stream) stream = trackingStream(Ray{origin, d}, 0.5f);
        const float active = std::min(length, gap + m.densityExtent(origin, d));  // empty beyond
        for (float t = 0.0f; majorant > 0.0f;) {
          t -= std::log1p(-stream->uniform()) / majorant;
          if (!(t < active)) break;
          const float dx = m.density(origin + std::max(t - gap, 0.0f) * d);
          for (size_t k = 0; k < n; ++k) ratio[k] *= std::max(0.0f, 1.0f - dx * sigma[k] / majorant);
        }
      }
    }
    if (!hit) {
      for (size_t k = 0; k < n; ++k) tr[k] = ratio[k] * std::exp(-tau[k]);
      return true;
    }
    medium = scene.mediumBeyond(*hit, d, medium);
    origin = offsetPoint(hit->p, hit->ng, d);
    for (size_t k = 0; depths && k < n; ++k) depths[k].crossesBoundary = true;
    tMax -= length;
    gap = crossingGap(*hit, d);
  }
  return false;
}

float freeFlightUniform(Sampler& rng, uint32_t firstDimension, int depth) {
  rng.setDimension(kFreeFlightDimensions + firstDimension + uint32_t(depth));
  const float u = rng.uniform();
  rng.startVertex(firstDimension, depth);
  return u;
}

}  // namespace kasha
