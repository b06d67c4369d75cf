#include "integrators/photon_mapping/direct_light_wavelengths.h"

#include <algorithm>
#include <memory>
#include <stdexcept>
#include <vector>

#include "core/color.h"

namespace kasha {
namespace {

constexpr float kTableStep = 0.5f;  // nm between the table's knots

}  // namespace

std::optional<WavelengthDensity> directLightWavelengths(const WavelengthSources& sources, const std::string& setting) {
  if (setting == "camera") return std::nullopt;
  if (setting == "cmf*light") {
    // One table, sampled by its own inverse CDF so that the lanes' strata stay strata:
    // (1 − κ)·(1/3)·Σ_c c̄·ΣΦ/∫c̄·ΣΦ over c̄ = x̄, ȳ, z̄ (each channel's direct elastic integrand under
    // grey surfaces, a third of the mass each) + κ·W̄/∫W̄, W̄ = x̄ + ȳ + z̄ (photon-mapping.md §3).
    const WavelengthRange seen = sources.seen;
    const Observer& o = Observer::cie1931();
    const Spectrum* channels[3] = {&o.xbar, &o.ybar, &o.zbar};
    std::vector<float> lambdas;
    for (int i = 0;; ++i) {
      lambdas.push_back(std::min(seen.min + float(i) * kTableStep, seen.max));
      if (lambdas.back() >= seen.max) break;
    }
    std::vector<double> products[3], cmf(lambdas.size());
    double integral[3] = {}, cmfIntegral = 0.0;  // Σ over the knots: the same step everywhere but the last
    for (size_t i = 0; i < lambdas.size(); ++i) {
      for (int c = 0; c < 3; ++c) {
        products[c].push_back(double((*channels[c])(lambdas[i])) * double(sources.lightPower(lambdas[i])));
        integral[c] += products[c].back();
      }
      cmfIntegral += cmf[i] = double(sources.colorMatching->pdf(lambdas[i]));
    }
    int lit = 0;  // channels the lights reach
    for (const double v : integral) lit += v > 0.0 ? 1 : 0;
    std::vector<float> values(lambdas.size());
    for (size_t i = 0; i < lambdas.size(); ++i) {
      double product = 0.0;
      for (int c = 0; c < 3; ++c)
        if (integral[c] > 0.0) product += products[c][i] / (integral[c] * lit);
      values[i] = float((lit > 0 ? (1.0 - kColorMatchingShare) * product : 0.0) + kColorMatchingShare * cmf[i] / cmfIntegral);
    }
    WavelengthDensity d;
    d.add(std::make_shared<const SpectralDistribution>(Spectrum::piecewiseLinear(lambdas, values), seen), 1.0f);
    return d;
  }
  try {
    const WavelengthSpec spec = parseWavelengthSpec(setting);
    return WavelengthStrategy(spec, sources, WavelengthSite::Sensor).density();
  } catch (const std::invalid_argument& e) {
    throw PpmNeeWavelengthsError("'" + setting + "': " + e.what());
  }
}

}  // namespace kasha
