#include "integrators/lane_light_choice.h"

#include <algorithm>

namespace kasha {

void LaneLightTable::reset(const Scene& scene, std::span<const float> lambda, bool perLane) {
  n_ = int(lambda.size());
  lights_ = scene.lights.size();
  power_.resize(size_t(n_) * lights_);
  total_.assign(size_t(n_), 0.0f);
  mixture_.assign(lights_, 0.0f);
  for (int k = 0; k < n_; ++k)
    for (size_t l = 0; l < lights_; ++l)
      total_[size_t(k)] += power_[size_t(k) * lights_ + l] = scene.lights[l]->power(lambda[size_t(k)]);
  single_.resize(perLane ? size_t(n_) * lights_ : 0);
  for (int k = 0; k < n_ && perLane; ++k) {
    const float selectorTotal = scene.lightSelector->totalPower(lambda[size_t(k)]);
    for (size_t l = 0; l < lights_; ++l)  // as LightSelector::probability
      single_[size_t(k) * lights_ + l] = selectorTotal > 0.0f ? power_[size_t(k) * lights_ + l] / selectorTotal : 0.0f;
  }
  for (size_t l = 0; l < lights_; ++l) {
    float sum = 0.0f;
    for (int k = 0; k < n_; ++k)
      if (total_[size_t(k)] > 0.0f) sum += power_[size_t(k) * lights_ + l] / total_[size_t(k)];
    mixture_[l] = sum / float(n_);
  }
}

std::pair<size_t, float> LaneLightTable::select(float u) const {
  // A lane J uniformly with u, then the light ∝ Φ_l(λ_J) with the rest of u.
  const int J = std::min(int(u * float(n_)), n_ - 1);
  const float v = std::min(u * float(n_) - float(J), kBelowOne);
  const float* power = &power_[size_t(J) * lights_];
  if (!(total_[size_t(J)] > 0.0f)) return {0, 0.0f};
  float acc = 0.0f;
  size_t chosen = lights_;
  for (size_t l = 0; l < lights_ && chosen == lights_; ++l) {
    if (power[l] <= 0.0f) continue;
    acc += power[l];
    if (v * total_[size_t(J)] < acc) chosen = l;
  }
  if (chosen == lights_)  // rounding: the last light that emits at λ_J
    for (size_t l = 0; l < lights_; ++l)
      if (power[l] > 0.0f) chosen = l;
  return {chosen, mixture_[chosen]};
}

void laneImportance(const Bsdf& bsdf, TransportMode mode, std::span<const float> known, const float* beforeMagnitude,
                    const LaneEvent& e, float* importance) {
  float every = 0.0f;    // what a fluorescent lane serving every lane serves
  int fluorescing = -1;  // a lane before that can fluoresce: its excitation density q_j ∝ absorption
  for (size_t j = 0; j < known.size(); ++j) {
    every += beforeMagnitude[j];
    if (fluorescing < 0 && e.lobe == SpectralLobe::Fluorescent && bsdf.fluorescenceProbability(mode, known[j]) > 0.0f)
      fluorescing = int(j);
  }
  for (int k = 0; k < e.n; ++k) {
    importance[k] = (e.source[k] == kEveryLane ? every : beforeMagnitude[e.source[k]]) * e.scale[k];
    if (e.lobe == SpectralLobe::Fluorescent)
      importance[k] *= fluorescing < 0 ? 0.0f : bsdf.spectralPdf(mode, known[size_t(fluorescing)], e.lambda[k], e.lobe);
  }
}

void LaneLightChoice::reset(const Scene& scene, std::span<const float> lambda, const float* importance, float byPower) {
  const size_t n = lambda.size(), lights = scene.lights.size();
  power_.resize(n * lights);
  pmf_.assign(lights, 0.0f);
  float total[kMaxLanes] = {};
  float weighted = 0.0f;  // Σ_k I_k·Φ(λ_k)
  for (size_t k = 0; k < n; ++k) {
    for (size_t l = 0; l < lights; ++l) total[k] += power_[k * lights + l] = scene.lights[l]->power(lambda[k]);
    weighted += importance[k] * total[k];
  }
  float sum = 0.0f;
  for (size_t l = 0; l < lights; ++l) {
    float byLane = 0.0f, byImportance = 0.0f;
    for (size_t k = 0; k < n; ++k) {
      if (total[k] > 0.0f) byLane += power_[k * lights + l] / total[k];
      byImportance += importance[k] * power_[k * lights + l];
    }
    pmf_[l] = (weighted > 0.0f ? byPower * byImportance / weighted : 0.0f) + (1.0f - byPower) * byLane / float(n);
    sum += pmf_[l];
  }
  if (sum > 0.0f)
    for (float& p : pmf_) p /= sum;
}

std::pair<size_t, float> LaneLightChoice::select(float u) const {
  size_t chosen = pmf_.size();
  float cdf = 0.0f;
  for (size_t l = 0; l < pmf_.size() && chosen == pmf_.size(); ++l) {
    cdf += pmf_[l];
    if (pmf_[l] > 0.0f && u < cdf) chosen = l;
  }
  if (chosen == pmf_.size())  // rounding: the last light with P(l) > 0
    for (size_t l = 0; l < pmf_.size(); ++l)
      if (pmf_[l] > 0.0f) chosen = l;
  if (chosen == pmf_.size()) return {0, 0.0f};
  return {chosen, pmf_[chosen]};
}

}  // namespace kasha
