#pragma once
// Spectral path tracing: camera subpaths in Radiance mode, each carrying N wavelengths, its lanes
// (hero wavelength sampling, Wilkie, Nawaz, Droske, Weidlich & Hanika 2014, with pbrt-v4's
// stratification and lanes that pass through fluorescent events; docs/wavelength-sampling.md
// "Hero wavelengths"). N = 1 is one wavelength per path.
//
// The camera's wavelengths. N > 1: the sensor density p at the stratified points (u + j/N) mod 1
// of its inverse CDF, so that every lane is distributed as p and the N lanes cover it evenly; every
// choice along the path is symmetric in the lanes (the lobe with the mean of their P_c, Jung18
// eq. 7; the light from the lanes' weights and the lights' power at them, LaneLightChoice;
// directions where their density is the same for every lane), so the balance heuristic over the N
// hero techniques (Wilkie14 eq. 8) weights every lane by 1/(N·p(λ_j)). A lane carries its XYZ
// throughput (a 3-vector), not a scalar; when the render keeps spectral bins, its throughput per
// sensor wavelength instead (SensorShares), so that each share reaches its own bin even after a
// fluorescent event has mixed the lanes. An area emitter seen directly by the camera ray adds its
// exact XYZ (its L_e(λ) is known at every λ; no MIS there), except with SensorShares. N = 1: any
// sensor strategy, multi-sample MIS included (one path per draw, weighted by the draw's MIS weight
// over its density); the lane's throughput is a scalar, the sensor responds at the end at the
// wavelength arriving at it (transport.md §1), and next-event estimation takes the scene's light
// choice at its wavelength (LightSelector, which LaneLightChoice reduces to with one lane).
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
//
// Next-event estimation serves every lane with one light sample (lane_next_event.h) and is combined
// with direction sampling by the power heuristic over directions (the choice of the wavelengths,
// common to both, cancels) — unless, with N = 1, the nee strategy draws next-event estimation's own
// λ_i after a fluorescent event, when the weights compare the full densities, wavelength included.
#include <vector>

#include "scene/wavelength_strategy.h"
#include "integrators/fluorescence_sampling.h"
#include "integrators/integrator.h"
#include "integrators/sensor_shares.h"
#include "integrators/wavelength_lanes.h"

namespace kasha {

class PathTracer final : public Integrator {
 public:
  // settings.heroWavelengths lanes in [1, kMaxLanes] (kAutoLanes resolved, as makeIntegrator does);
  // with more than one, the sensor strategy must be a density and nee_sampling "event". Throws
  // std::invalid_argument (WavelengthStrategyError for a strategy) otherwise.
  PathTracer(const Scene& scene, const RenderSettings& settings);
  Vec3 samplePixel(const Scene& scene, Vec2 pixel, Sampler& rng, SampleContext& ctx) const override;
  std::string name() const override { return "pt"; }
  int lanes() const override { return n_; }

 private:
  // The radiance over density arriving along the camera ray, in the lanes' throughput type T:
  // XYZ (Vec3) or SensorShares with N > 1, a scalar (float) with N = 1.
  template <class T>
  T radiance(const Scene& scene, Ray ray, PathLanes<T>& lanes, Sampler& rng, RayCounter& counter) const;

  WavelengthSources sources_;
  WavelengthStrategy sensor_;
  FluorescenceSampling excitation_;  // λ_i given the fluorescent lobe ("material": the Bsdf's own)
  FluorescenceSampling nee_;         // λ_i of next-event estimation after a fluorescent event ("event": the event's)
  int n_;
  FluorescentLanes atFluorescence_;
  int maxDepth_, rrDepth_;
  bool hideEmitters_;  // RenderSettings::hideEmitters
  std::vector<Vec3> directXyz_;  // per light: its emission's XYZ seen directly (direct_emission.h)
};

}  // namespace kasha
