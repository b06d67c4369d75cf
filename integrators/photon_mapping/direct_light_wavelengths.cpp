#include "integrators/photon_mapping/direct_light_wavelengths.h"

#include <algorithm>
#include <memory>
#include <stdexcept>
#include <vector>

namespace kasha {
namespace {

constexpr float kProductStep = 0.5f;  // nm between the product's knots

}  // namespace

std::optional<WavelengthDensity> directLightWavelengths(const WavelengthSources& sources, const std::string& setting) {
  if (setting == "camera") return std::nullopt;
  if (setting == "cmf*light") {
    // The direct elastic integrand of a grey surface under the lights, W̄(λ)·Σ_l Φ_l(λ) (photon-mapping.md §3).
    const WavelengthRange seen = sources.seen;
    std::vector<float> lambdas, values;
    for (int i = 0;; ++i) {
      const float lambda = std::min(seen.min + float(i) * kProductStep, seen.max);
      lambdas.push_back(lambda);
      values.push_back(sources.colorMatching->pdf(lambda) * sources.lightPower(lambda));
      if (lambda >= seen.max) break;
    }
    WavelengthDensity d;
    const auto product = std::make_shared<const SpectralDistribution>(Spectrum::piecewiseLinear(lambdas, values), seen);
    if (product->integral() > 0.0f) d.add(product, 1.0f - kDefensiveColorMatching);
    d.add(sources.colorMatching, kDefensiveColorMatching);
    return d;
  }
  try {
    const WavelengthSpec spec = parseWavelengthSpec(setting);
    return WavelengthStrategy(spec, sources, WavelengthSite::Sensor).density();
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument("ppm: render/ppm/nee_wavelengths '" + setting + "': " + e.what());
  }
}

}  // namespace kasha
