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
  for (const WavelengthSources::Fluorophore& f : sources.fluorophores)
    perMaterial_[f.material] = std::make_unique<WavelengthStrategy>(spec, sources, site, f.material);
}

SpectralChoice FluorescenceSampling::sample(const Bsdf& bsdf, size_t m, float lambdaOut, float u) const {
  const WavelengthStrategy* s = perMaterial_[m].get();
  if (!s) return bsdf.sampleSpectral(TransportMode::Radiance, lambdaOut, u);
  const float pF = bsdf.fluorescenceProbability(TransportMode::Radiance, lambdaOut);
  if (u < pF) {
    const WavelengthSample ws = s->density().sample(std::min(u / pF, 0x1.fffffep-1f));
    if (ws.pdf <= 0.0f) return {};
    return {SpectralLobe::Fluorescent, ws.lambda, pF * ws.pdf};
  }
  const float pElastic = bsdf.spectralPdf(TransportMode::Radiance, lambdaOut, lambdaOut, SpectralLobe::Elastic);
  if (pElastic <= 0.0f) return {};
  return {SpectralLobe::Elastic, lambdaOut, pElastic};
}

WavelengthSample FluorescenceSampling::sampleExcitation(size_t m, float u) const {
  return perMaterial_[m] ? perMaterial_[m]->density().sample(u) : WavelengthSample{};
}

float FluorescenceSampling::pdf(const Bsdf& bsdf, size_t m, float lambdaOut, float lambdaIn,
                                SpectralLobe lobe) const {
  const WavelengthStrategy* s = perMaterial_[m].get();
  if (!s || lobe == SpectralLobe::Elastic) return bsdf.spectralPdf(TransportMode::Radiance, lambdaOut, lambdaIn, lobe);
  return bsdf.fluorescenceProbability(TransportMode::Radiance, lambdaOut) * s->density().pdf(lambdaIn);
}

}  // namespace kasha
