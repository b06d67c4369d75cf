#include "integrators/bidirectional/light_first.h"

#include <algorithm>

namespace kasha::bidir {

LightFirstStart::LightFirstStart(const Scene& scene, const WavelengthSpec& lightStart) {
  requireDensity(lightStart, WavelengthSite::LightStart, "by bdpt (its MIS weights need the light-start density)");
  const size_t n = scene.lights.size();
  pmf_.assign(n, 0.0f);
  perLight_.resize(n);
  double total = 0.0;
  for (size_t l = 0; l < n; ++l) {
    const Light& light = *scene.lights[l];
    const Spectrum power = light.spectrum().scaled(light.powerFactor() * light.scale());
    const float integral = power.integral(scene.range);
    if (!(integral > 0.0f)) continue;
    // The scene's sources with this light's power in place of all lights': a strategy such as
    // `light` or `mix:light,uniform` then draws from this light's spectrum.
    WavelengthSources own(scene);
    own.lightPower = power;
    perLight_[l] = WavelengthStrategy(lightStart, own, WavelengthSite::LightStart).density();
    pmf_[l] = integral;
    total += integral;
  }
  cdf_.resize(n);
  double run = 0.0;
  for (size_t l = 0; l < n; ++l) {
    pmf_[l] = total > 0.0 ? float(pmf_[l] / total) : 0.0f;
    run += pmf_[l];
    cdf_[l] = float(run);
  }
}

LightFirstStart::Draw LightFirstStart::sample(float uLight, float uLambda) const {
  if (cdf_.empty() || !(cdf_.back() > 0.0f)) return {};
  const float u = uLight * cdf_.back();
  size_t l = size_t(std::upper_bound(cdf_.begin(), cdf_.end(), u) - cdf_.begin());
  l = std::min(l, cdf_.size() - 1);
  while (pmf_[l] <= 0.0f && l > 0) --l;  // the rounding at the top of the table
  if (pmf_[l] <= 0.0f) return {};
  const WavelengthSample ws = perLight_[l].sample(uLambda);
  if (!(ws.pdf > 0.0f)) return {};
  return {l, ws.lambda, pmf_[l], ws.pdf};
}

float LightFirstStart::wavelengthPdf(size_t light, float lambda) const {
  return perLight_[light].empty() ? 0.0f : perLight_[light].pdf(lambda);
}

}  // namespace kasha::bidir
