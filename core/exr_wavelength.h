#pragma once
// Wavelengths in OpenEXR channel names, as the spectral layout of Fichet, Pacanowski & Wilkie
// (2021, JCGT 10(3), "An OpenEXR Layout for Spectral Images", §3) writes them: a number with a
// decimal comma and an optional exponent, then a unit, m or Hz with an optional SI prefix
// ("550,000000nm", "0,45um", "5,5e2nm", "600THz"). Used by the bispectral (T.*) and the
// emissive (S0.*) channels.
#include <optional>
#include <string>

namespace kasha {

// The wavelength in nm of one part of a channel name; empty if it is not a wavelength.
std::optional<float> parseExrWavelength(const std::string& part);
// "550,000000nm": the name part kasha writes for a wavelength in nm.
std::string exrWavelengthName(float nm);

}  // namespace kasha
