#pragma once
// The wavelengths of photon mapping's next-event estimation for the elastic lobe at the first
// camera vertex (docs/photon-mapping.md §3, "Wavelengths of the direct elastic light"). There the
// camera ray does not depend on λ, so next-event estimation may draw lanes of its own and take the
// sensor at each: the density that suits the direct elastic integrand W(λ)·f(λ)·L_e(λ)·G, not the
// camera's, which a narrow light's line may fall outside.
#include <optional>
#include <string>

#include "core/wavelength_density.h"
#include "scene/wavelength_strategy.h"

namespace kasha {

// Share of the colour-matching density in "cmf*light" (defensive importance sampling, Hesterberg
// 1995): it keeps every wavelength the sensor sees covered, whatever the tabulated product misses.
inline constexpr float kDefensiveColorMatching = 0.1f;

// The density of render/ppm/nee_wavelengths `setting` (ppmNeeWavelengthsError has accepted it),
// or nullopt for "camera" (the camera path's own lanes). "cmf*light":
// (1 − κ)·(x̄+ȳ+z̄)(λ)·Σ_l Φ_l(λ)/∫… + κ·p_cmf(λ), κ = kDefensiveColorMatching (the product
// tabulated every 0.5 nm where the observer sees; p_cmf alone if no light emits there). Anything
// else is a wavelength strategy built at the sensor site. Throws std::invalid_argument (naming the
// setting) if the strategy does not apply to the scene.
std::optional<WavelengthDensity> directLightWavelengths(const WavelengthSources& sources, const std::string& setting);

}  // namespace kasha
