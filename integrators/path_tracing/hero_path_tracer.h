#pragma once
// Path tracing with wavelength lanes (hero wavelength sampling, Wilkie, Nawaz, Droske, Weidlich &
// Hanika 2014, with pbrt-v4's stratification and lanes that pass through fluorescent events;
// docs/wavelength-sampling.md "Lanes"). Each camera path carries N wavelengths drawn from the
// sensor density p at the stratified points (u + j/N) mod 1 of its inverse CDF, so that every lane
// is distributed as p and the N lanes cover it evenly. An area emitter seen directly by the camera
// ray adds its exact XYZ instead (its L_e(λ) is known at every λ; no MIS there). Every choice along the path is symmetric in the lanes (the lobe with the mean of their
// P_c, Jung18 eq. 7; the light from the lanes' weights and the lights' power at them, LaneLightChoice;
// directions where their density is the same for every lane), so the balance heuristic over the N hero techniques (Wilkie14 eq. 8) weights every lane by
// 1/(N·p(λ_j)). A lane carries its XYZ throughput (a 3-vector), not a scalar; when the render
// keeps spectral bins, its throughput per sensor wavelength instead (SensorShares), so that each
// share reaches its own bin even after a fluorescent event has mixed the lanes (the directly seen
// emitter then takes the lanes' estimate too).
//
// At a fluorescent event the lanes do not end. The event's value for lane j is the integral over
// λ_i of f(λ_i → λ_o^j)·L(λ_i); the excitation density does not depend on which λ_o it serves (a
// strategy's density, or the Bsdf's own given λ_o^j used as a mixture over the lanes), so a fresh
// set of N excitation lanes λ_k serves every λ_o^j at once: lane k carries
//   T_k = Σ_j T_j·f(λ_k → λ_o^j)·|cos θ| / (P_fl · pdf_dir · Σ_m n_m q_m(λ_k))
// (Veach's multi-sample balance heuristic over the mixture components q_m, n_m samples of each).
// Wherever the Bsdf's elastic direction sampling depends on λ (BsdfFlags::WavelengthDependentDirection)
// the lanes end before next-event estimation, keeping one chosen uniformly at random with its weight
// times N (one-sample estimate of the sum over lanes; pbrt-v4's TerminateSecondary keeps the hero,
// which is unbiased only when each lane alone is, unlike the lanes after a mixture). With
// settings.fluorescentLanes = End (an experiment) they end at fluorescent events too, one kept
// with odds its fluorescent-lobe probability, and the path goes on with one lane, as ART,
// Mojzík et al. and pbrt-style renderers do.
#include "scene/wavelength_strategy.h"
#include "integrators/fluorescence_sampling.h"
#include "integrators/integrator.h"
#include "integrators/sensor_shares.h"
#include "integrators/wavelength_lanes.h"

namespace kasha {

class HeroPathTracer final : public Integrator {
 public:
  static constexpr int kMaxWavelengths = kMaxLanes;
  // settings.heroWavelengths in [2, kMaxWavelengths]; the sensor strategy must be a density.
  // Throws std::invalid_argument (WavelengthStrategyError for a strategy) otherwise.
  HeroPathTracer(const Scene& scene, const RenderSettings& settings);
  Vec3 samplePixel(const Scene& scene, Vec2 pixel, Sampler& rng, SampleContext& ctx) const override;
  std::string name() const override { return "pt"; }
  int lanes() const override { return n_; }

 private:
  // The radiance over density arriving along the camera ray, in the lanes' throughput type T:
  // XYZ (Vec3), or SensorShares.
  template <class T>
  T radiance(const Scene& scene, Ray ray, CameraLanesOf<T>& lanes, Sampler& rng, RayCounter& counter) const;

  WavelengthSources sources_;
  WavelengthStrategy sensor_;
  FluorescenceSampling excitation_;  // λ_i given the fluorescent lobe ("material": the Bsdf's own)
  int n_;
  FluorescentLanes atFluorescence_;
  int maxDepth_, rrDepth_;
  std::vector<Vec3> directXyz_;  // per light: its emission's XYZ seen directly (direct_emission.h)
};

}  // namespace kasha
