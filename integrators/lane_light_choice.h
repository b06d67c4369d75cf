#pragma once
// Choosing a light for N wavelength lanes (docs/wavelength-sampling.md "Choosing the light").
//
// LaneLightTable is symmetric in the lanes: a lane J uniformly, then light l ∝ Φ_l(λ_J), so that
// P(l) = (1/N)·Σ_k Φ_l(λ_k)/Φ(λ_k), the mixture over the N hero techniques. Each lane gets its share
// of the choices, however different the lights' powers at the lanes are (∝ Σ_k Φ_l(λ_k) would
// almost never pick a weak white light beside a strong UV one). Light subpaths start with it, and
// BDPT chooses and weighs its lights with it.
//
// LaneLightChoice is next-event estimation's for the lanes of a camera path (the path tracer and
// photon mapping). Next-event estimation at a
// vertex estimates Σ_k Σ_l C_kl (lane k's light from light l) with one light l ~ P(l); the choice
// adds no variance when P(l) ∝ Σ_k C_kl, and a light of one spectrum Φ_l(λ) gives lane k about
// I_k·Φ_l(λ_k), I_k the lane's weight. So
//   P(l) ∝ α·Σ_k I_k·Φ_l(λ_k)/Σ_k I_k·Φ(λ_k) + (1 − α)·(1/N)·Σ_k Φ_l(λ_k)/Φ(λ_k),  Φ = Σ_l Φ_l,
// normalised over the lights that emit at some lane. The second part alone (LaneLightTable's
// mixture) gives every lane the same share however bright
// the lights are at its wavelength — an excitation lane inside a narrow UV source got that light
// one time in N, which undid the lanes' gain on the UV scenes; with 1 − α it stays as a defensive
// share, so that every light that emits at some lane keeps a probability of at least
// (1 − α)/N·Φ_l(λ_k)/Φ(λ_k) for each lane k.
#include <span>
#include <utility>
#include <vector>

#include "integrators/wavelength_lanes.h"
#include "scene/light_selector.h"
#include "scene/scene.h"

namespace kasha {

class LaneLightTable {
 public:
  // Every light's power at every lane, evaluated once (BDPT chooses lights and weighs them several
  // times per camera sample); with `perLane`, also laneProbability's table (BDPT's weights need it,
  // a light subpath's start does not).
  void reset(const Scene& scene, std::span<const float> lambda, bool perLane = false);
  // The light chosen with u (a lane with the first part of u, the light with the rest) and P(l);
  // probability 0 if no light emits at the chosen lane.
  std::pair<size_t, float> select(float u) const;
  float probability(size_t light) const { return mixture_[light]; }
  // p(light | λ_k), LightSelector::probability at lane k's wavelength (after a reset with perLane).
  float laneProbability(size_t light, int k) const { return single_[size_t(k) * lights_ + light]; }

 private:
  int n_ = 0;
  size_t lights_ = 0;
  std::vector<float> power_;    // Φ_l(λ_k) at k·lights + l
  std::vector<float> total_;    // Σ_l Φ_l(λ_k)
  std::vector<float> mixture_;  // P(l)
  std::vector<float> single_;   // p(l | λ_k) at k·lights + l
};

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
  // is α (0: LaneLightTable's probabilities).
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
