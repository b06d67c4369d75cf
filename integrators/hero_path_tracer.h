#pragma once
// Path tracing with hero wavelength sampling (Wilkie, Nawaz, Droske, Weidlich & Hanika 2014,
// "Hero Wavelength Spectral Sampling"): each camera path carries N wavelengths, the hero λ_h drawn
// from the sensor density p and N − 1 rotations λ_j = λ_min + (λ_h − λ_min + j·W/N) mod W over the
// sensor's range of width W. Every choice along the path depends on the set of wavelengths, never
// on which one is the hero — the lobe with the mean of the lanes' P_c (Jung18 eq. 7), the light in
// proportion to Σ_j Φ_l(λ_j), directions only where their density is the same for every lane —
// so each of the N "hero" techniques that can produce the path has the same path density, and the
// balance heuristic over them (Wilkie14 eq. 8) divides every lane by Σ_k p(λ_k).
//
// At a fluorescent event, at a specular vertex, and before next-event estimation wherever the
// Bsdf's direction sampling depends on λ (BsdfFlags::WavelengthDependentDirection: dispersion,
// lobe choices weighted by a spectrum; next-event estimation would otherwise weight every lane
// with the hero's direction density), the secondary wavelengths end and the hero continues alone (Mojzík,
// Fichet & Wilkie 2018, "Handling fluorescence in a uni-directional spectral path tracer"): no other
// technique can produce what follows, so from there on the hero is weighted by 1/p(λ_h) alone.
#include "scene/wavelength_strategy.h"
#include "integrators/fluorescence_sampling.h"
#include "integrators/integrator.h"

namespace kasha {

class HeroPathTracer final : public Integrator {
 public:
  static constexpr int kMaxWavelengths = 16;
  // settings.heroWavelengths in [2, kMaxWavelengths]; the sensor strategy must be a density.
  // Throws std::invalid_argument (WavelengthStrategyError for a strategy) otherwise.
  HeroPathTracer(const Scene& scene, const RenderSettings& settings);
  Vec3 samplePixel(const Scene& scene, Vec2 pixel, Sampler& rng, SampleContext& ctx) const override;
  std::string name() const override { return "pt"; }

 private:
  struct Lanes {
    int n = 0;                       // active lanes; lane 0 is the hero
    float lambda[kMaxWavelengths];   // the wavelength of the current segment
    float beta[kMaxWavelengths];     // throughput over the (shared) path density
    float L[kMaxWavelengths];        // radiance gathered
  };
  void radiance(const Scene& scene, Ray ray, Lanes& lanes, float collapseFactor, Sampler& rng, RayCounter& counter) const;
  // Probability of choosing light `light` for next-event estimation: ∝ Σ_j Φ_light(λ_j).
  float lightSelectProbability(const Scene& scene, size_t light, const Lanes& lanes) const;
  std::pair<size_t, float> selectLight(const Scene& scene, const Lanes& lanes, float u) const;

  WavelengthSources sources_;
  WavelengthStrategy sensor_;
  FluorescenceSampling excitation_;  // λ_i given the fluorescent lobe ("material": the Bsdf's own)
  int n_, maxDepth_, rrDepth_;
};

}  // namespace kasha
