#pragma once
// Wavelength lanes (docs/wavelength-sampling.md "Hero wavelengths"): a path carries N wavelengths
// at once. These are the pieces every lane-carrying integrator shares, in either transport mode:
// the spectral event of all lanes at a vertex — elastic (each lane keeps its wavelength) or
// fluorescent (a fresh set of N lanes at the sampled side's wavelength, each serving every lane
// before it, Veach's multi-sample balance heuristic over the lanes' densities; or, with
// FluorescentLanes::End, one lane per lane before it, to be ended in one) — each new lane's
// weight through that event for a direction, and ending the lanes in one chosen at random.
#include <span>
#include <vector>

#include "core/wavelength_density.h"
#include "materials/bsdf.h"
#include "scene/render_settings.h"
#include "scene/scene.h"

namespace kasha {

inline constexpr int kMaxLanes = 16;

// The k-th of n stratified points from u in [0, 1): (u + k/n) mod 1.
float laneStratum(float u, int k, int n);

// The n wavelengths a path starts with (compare pbrt-v4's SampledWavelengths): lane k at the
// stratum (u + k/n) of one density's inverse CDF (Wilkie14), with its density p(λ_k). Every
// integrator draws its lanes so: the camera's from the sensor density, the light's from the
// light-start density.
struct SampledLanes {
  int n = 0;
  float lambda[kMaxLanes];
  float pdf[kMaxLanes];
  std::span<const float> wavelengths() const { return {lambda, size_t(n)}; }
};
SampledLanes sampleLanes(const WavelengthDensity& density, float u, int n);

// A path's lanes between two vertices: each lane's wavelength and throughput, of type T (a light
// path's flux, a float; a camera path's XYZ, or its SensorShares where spectral bins are kept).
template <class T>
struct PathLanes {
  int n = 0;
  float lambda[kMaxLanes];
  T beta[kMaxLanes];
  std::span<const float> wavelengths() const { return {lambda, size_t(n)}; }
};
// The magnitude of a lane's throughput: what Russian roulette and the light choice compare.
inline float magnitude(float beta) { return beta; }
inline float magnitude(const Vec3& beta) { return beta.x + beta.y + beta.z; }
// Σ_k of the lanes' magnitudes.
template <class T>
float magnitude(const PathLanes<T>& lanes) {
  float m = 0.0f;
  for (int k = 0; k < lanes.n; ++k) m += magnitude(lanes.beta[k]);
  return m;
}

// The spectral event at a vertex for every lane. "Known" wavelengths are the lanes' before the
// event (λ_o in Radiance mode, λ_i in Importance mode); lambda[k] is lane k's on the sampled side.
struct LaneEvent {
  SpectralLobe lobe = SpectralLobe::Elastic;
  int n = 0;                  // lanes after the event; 0 if nothing scatters
  float lambda[kMaxLanes];    // the sampled side's wavelength of each lane
  float scale[kMaxLanes];     // 1 / the event's spectral density for this lane
  // The lane before the event that this one continues (elastic, or fluorescent with
  // FluorescentLanes::End), or kEveryLane: a fluorescent lane that serves every lane before it.
  int source[kMaxLanes];
  bool ended = false;         // fluorescent lanes one per lane before (FluorescentLanes::End): keep one
  // The odds of keeping lane k where the lanes end (keepOneLane): equal, but for ended fluorescent
  // lanes the fluorescent-lobe probability at the wavelength of the lane before.
  float odds[kMaxLanes];
};
inline constexpr int kEveryLane = -1;

// Chooses the lobe for every lane at once — fluorescent with the mean of the lanes' probabilities
// (Jung18 eqs. 6/7 per lane), so the choice is symmetric in them — from the uniform u. Fluorescent,
// FluorescentLanes::Through: `fresh` new lanes at the strata of u/P̄ of `strategy`'s inverse CDF
// if given (its density must not depend on the known wavelength), else of the Bsdf's own densities
// given each known wavelength, as a mixture over the lanes that can fluoresce.
// FluorescentLanes::End: new lane k at the k-th stratum serves known lane k alone, drawn as a
// single-wavelength path draws it (the strategy, else the Bsdf's own density given known[k]);
// e.ended asks the caller to keep one of them (keepOneLane, with odds P(λ_k)), which makes the
// event a one-sample estimate over the lanes before it: lane k goes on after a fluorescent event
// with probability P̄·P(λ_k)/(N·P̄) = P(λ_k)/N, as if a single-wavelength path at λ_k had chosen it.
LaneEvent sampleLaneEvent(const Bsdf& bsdf, TransportMode mode, std::span<const float> known, int fresh, float u,
                          const WavelengthDensity* strategy = nullptr,
                          FluorescentLanes atFluorescence = FluorescentLanes::Through);

// Lane k's weight through event e for the sampled direction wSampled (without |cos θ|): a lane
// that continues one lane j = e.source[k] (elastic, or fluorescent with FluorescentLanes::End),
// before[j]·f(between known[j] and lambda[k]); one that serves every lane,
// Σ_j before[j]·f(between known[j] and lambda[k]). T is the throughput type (XYZ for camera paths,
// a scalar for light paths).
template <class T>
T laneWeight(const Bsdf& bsdf, TransportMode mode, std::span<const float> known, const T* before, const LaneEvent& e,
             int k, const Vec3& wSampled, const Vec3& wKnown) {
  const bool radiance = mode == TransportMode::Radiance;
  const Vec3& wi = radiance ? wSampled : wKnown;
  const Vec3& wo = radiance ? wKnown : wSampled;
  const auto f = [&](size_t j) {
    return radiance ? bsdf.eval({mode, e.lobe, e.lambda[k], known[j]}, wi, wo)
                    : bsdf.eval({mode, e.lobe, known[j], e.lambda[k]}, wi, wo);
  };
  if (e.source[k] != kEveryLane) return before[e.source[k]] * (f(size_t(e.source[k])) * e.scale[k]);
  T sum = before[0] * 0.0f;
  for (size_t j = 0; j < known.size(); ++j) sum += before[j] * f(j);
  return sum * e.scale[k];
}

// Ends the lanes in one, lane j chosen with u with probability odds[j]/Σ odds (uniformly but for
// ended fluorescent lanes), its weight divided by that probability: an unbiased one-sample
// estimate of the sum over the lanes, however they were drawn.
void keepOneLane(LaneEvent& e, float u);

// True where the lanes of event e must end in one (keepOneLane) before next-event estimation: an
// elastic lobe whose direction sampling depends on λ, or fluorescent lanes drawn with
// FluorescentLanes::End.
bool lanesEndAt(const LaneEvent& e, const Bsdf& bsdf);

}  // namespace kasha
