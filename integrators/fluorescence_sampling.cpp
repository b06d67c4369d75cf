#include "integrators/fluorescence_sampling.h"

#include <algorithm>

namespace kasha {

FluorescenceSampling::FluorescenceSampling(const WavelengthSpec& spec, const WavelengthSources& sources,
                                           size_t materialCount, WavelengthSite site)
    : perMaterial_(materialCount) {
  const bool nee = site == WavelengthSite::Nee;
  if (spec.uses(nee ? WavelengthSpec::Kind::Event : WavelengthSpec::Kind::Material)) return;
  if (spec.uses(nee ? WavelengthSpec::Kind::Material : WavelengthSpec::Kind::Event))
    throw WavelengthStrategyError(site, std::string("wavelength strategy '") + spec.text + "' applies only to " +
                                            (nee ? "fluorescence_sampling (here: 'event' or a density, e.g. "
                                                   "'absorption')"
                                                 : "nee_sampling"));
  requireDensity(spec, site, "at fluorescent events");
  if (!sources.opaqueFluorescent.empty())
    throw WavelengthStrategyError(site, std::string("wavelength strategy '") + spec.text +
                                            "' needs every fluorescent material's absorption, and material '" +
                                            sources.opaqueFluorescent.front() +
                                            "' does not give it (only untextured jung_fluorescent does)");
  for (const WavelengthSources::Fluorophore& f : sources.fluorophores)
    perMaterial_[f.material] = std::make_unique<WavelengthStrategy>(spec, sources, site, f.material);
}

SpectralChoice FluorescenceSampling::sample(const Material& material, size_t m, float lambdaOut, float u) const {
  const WavelengthStrategy* s = perMaterial_[m].get();
  if (!s) return material.sampleSpectral(TransportMode::Radiance, lambdaOut, u);
  const float pF = material.fluorescenceProbability(TransportMode::Radiance, lambdaOut);
  if (u < pF) {
    const WavelengthSample ws = s->density().sample(std::min(u / pF, 0x1.fffffep-1f));
    if (ws.pdf <= 0.0f) return {};
    return {SpectralLobe::Fluorescent, ws.lambda, pF * ws.pdf};
  }
  const float pElastic = material.spectralPdf(TransportMode::Radiance, lambdaOut, lambdaOut, SpectralLobe::Elastic);
  if (pElastic <= 0.0f) return {};
  return {SpectralLobe::Elastic, lambdaOut, pElastic};
}

WavelengthSample FluorescenceSampling::sampleExcitation(size_t m, float u) const {
  return perMaterial_[m] ? perMaterial_[m]->density().sample(u) : WavelengthSample{};
}

float FluorescenceSampling::pdf(const Material& material, size_t m, float lambdaOut, float lambdaIn,
                                SpectralLobe lobe) const {
  const WavelengthStrategy* s = perMaterial_[m].get();
  if (!s || lobe == SpectralLobe::Elastic) return material.spectralPdf(TransportMode::Radiance, lambdaOut, lambdaIn, lobe);
  return material.fluorescenceProbability(TransportMode::Radiance, lambdaOut) * s->density().pdf(lambdaIn);
}

}  // namespace kasha
