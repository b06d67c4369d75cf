#pragma once
// The wavelengths of photon mapping's next-event estimation for the elastic lobe at the first
// camera vertex (docs/photon-mapping.md §3, "Wavelengths of the direct elastic light"). There the
// camera ray does not depend on λ, so next-event estimation may draw lanes of its own and take the
// sensor at each: the density that suits the direct elastic integrand W(λ)·f(λ)·L_e(λ)·G, not the
// camera's, which a narrow light's line may fall outside.
#include <optional>
#include <stdexcept>
#include <string>

#include "core/wavelength_density.h"
#include "scene/wavelength_strategy.h"

namespace kasha {

// Share of the colour-matching density in "cmf*light": it keeps every wavelength the sensor sees
// covered (defensive importance sampling, Hesterberg 1995), whatever the tabulated products miss,
// and the four lanes' strata close to the colour-matching ones under broad lights.
inline constexpr float kColorMatchingShare = 0.1f;

// A render/ppm/nee_wavelengths strategy that does not apply to the scene (the message says why).
struct PpmNeeWavelengthsError : std::invalid_argument {
  using std::invalid_argument::invalid_argument;
};

// The density of render/ppm/nee_wavelengths `setting` (ppmNeeWavelengthsError has accepted it),
// or nullopt for "camera" (the camera path's own lanes). "cmf*light", tabulated every 0.5 nm where
// the observer sees: (1 − κ)·(1/3)·Σ_c c̄(λ)·Σ_l Φ_l(λ)/∫c̄·ΣΦ over c̄ = x̄, ȳ, z̄ + κ·p_cmf(λ),
// κ = kColorMatchingShare (the channels no light reaches left out; p_cmf alone if none). Anything
// else is a wavelength strategy built at the sensor site. Throws PpmNeeWavelengthsError if the
// strategy does not apply to the scene.
std::optional<WavelengthDensity> directLightWavelengths(const WavelengthSources& sources, const std::string& setting);

}  // namespace kasha
