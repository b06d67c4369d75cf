#pragma once
// Next-event estimation's light choice for the wavelength lanes of a camera path (the path tracer
// and photon mapping; docs/wavelength-sampling.md "Choosing the light"). Next-event estimation at a
// vertex estimates Σ_k Σ_l C_kl (lane k's light from light l) with one light l ~ P(l); the choice
// adds no variance when P(l) ∝ Σ_k C_kl, and a light of one spectrum Φ_l(λ) gives lane k about
// I_k·Φ_l(λ_k), I_k the lane's weight. So
//   P(l) ∝ α·Σ_k I_k·Φ_l(λ_k)/Σ_k I_k·Φ(λ_k) + (1 − α)·(1/N)·Σ_k Φ_l(λ_k)/Φ(λ_k),  Φ = Σ_l Φ_l,
// normalised over the lights that emit at some lane. The second part alone (selectLaneLight: a
// lane uniformly, then a light ∝ its power there) gives every lane the same share however bright
// the lights are at its wavelength — an excitation lane inside a narrow UV source got that light
// one time in N, which undid the lanes' gain on the UV scenes; with 1 − α it stays as a defensive
// share, so that every light that emits at some lane keeps a probability of at least
// (1 − α)/N·Φ_l(λ_k)/Φ(λ_k) for each lane k.
#include <span>
#include <utility>
#include <vector>

#include "scene/light_selector.h"
#include "integrators/wavelength_lanes.h"

namespace kasha {

// α, the share of the choice that follows the lanes' weighted power.
inline constexpr float kNeeLightsByPower = 0.9f;

// Lane k's importance I_k after event e, for the light choice: the throughput magnitude of the
// lanes before it serves (beforeMagnitude[j] for lane j) times e.scale[k], and for a fluorescent
// lane times the Bsdf's own excitation (emission) density at its wavelength, which is ∝ the
// absorption (Kasha's rule: f = c·a(λ_i)·Q·e(λ_o)/π), so that I_k follows lane k's weight up to
// the direction factors all lanes share. Equal for fluorescent lanes of the material's own density;
// ∝ a(λ_k)/p(λ_k) for a strategy's p.
void laneImportance(const Bsdf& bsdf, TransportMode mode, std::span<const float> known, const float* beforeMagnitude,
                    const LaneEvent& e, float* importance);

class LaneLightChoice {
 public:
  // The choice for the lanes at wavelengths `lambda` of importance I_k (laneImportance); byPower
  // is α (0: selectLaneLight's probabilities).
  void reset(const Scene& scene, std::span<const float> lambda, const float* importance,
             float byPower = kNeeLightsByPower);
  // The light chosen with u (inverting the CDF of P, which keeps u's stratification) and P(l);
  // probability 0 if no light emits at any lane.
  std::pair<size_t, float> select(float u) const;
  float probability(size_t light) const { return pmf_[light]; }

 private:
  std::vector<float> power_;  // Φ_l(λ_k) at k·lights + l
  std::vector<float> pmf_;    // P(l)
};

// The choice for one lane at wavelength λ: the scene's LightSelector, P(l) = Φ_l(λ)/Φ(λ), which
// both parts of LaneLightChoice's P(l) reduce to with one lane, without a table per vertex.
struct OneLaneLightChoice {
  const LightSelector& selector;
  float lambda;
  std::pair<size_t, float> select(float u) const { return selector.select(lambda, u); }
  float probability(size_t light) const { return selector.probability(light, lambda); }
};

}  // namespace kasha
