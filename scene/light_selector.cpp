#include "scene/light_selector.h"

namespace kasha {

LightSelector::LightSelector(const std::vector<std::unique_ptr<Light>>& lights) : lights_(lights) {
  std::vector<std::pair<float, const Spectrum*>> terms;
  for (const auto& l : lights) terms.emplace_back(l->powerFactor() * l->scale(), &l->spectrum());
  totalPower_ = Spectrum::weightedSum(terms);
}

std::pair<size_t, float> LightSelector::select(float lambda, float u) const {
  const float total = totalPower_(lambda);
  if (!(total > 0.0f)) return {0, 0.0f};
  float acc = 0.0f;
  const float target = u * total;
  size_t last = 0;
  for (size_t i = 0; i < lights_.size(); ++i) {
    const float p = lights_[i]->power(lambda);
    if (p <= 0.0f) continue;
    last = i;
    acc += p;
    if (target < acc) return {i, p / total};
  }
  return {last, lights_[last]->power(lambda) / total};
}

float LightSelector::probability(size_t light, float lambda) const {
  const float total = totalPower_(lambda);
  return total > 0.0f ? lights_[light]->power(lambda) / total : 0.0f;
}

LightSelector::LightWavelength LightSelector::sampleLightAndWavelength(const WavelengthDensity& wavelengths,
                                                                      float uLambda, float uLight) const {
  const WavelengthSample ws = wavelengths.sample(uLambda);
  if (ws.pdf <= 0.0f) return {};
  const auto [light, p] = select(ws.lambda, uLight);
  if (p <= 0.0f) return {};
  return {light, ws.lambda, p * ws.pdf};
}

}  // namespace kasha
