#pragma once
// Bispectral OpenEXR files in the layout of Fichet, Pacanowski & Wilkie (2021), "An OpenEXR Layout
// for Spectral Images", JCGT 10(3), §3: reflective channels "T.<λ>" (the diagonal) and reradiation
// channels "T.<λ_i>.<λ_o>", each wavelength written as a number with a decimal comma followed by a
// unit (core/exr_wavelength.h: "T.550,000000nm", "T.0,45um.0,6um", "T.600THz").
// Other channels (RGB previews, emissive "S0.*") are ignored. A measurement is one pixel: the
// first pixel of the data window is read.
#include <optional>
#include <string>

#include "core/bispectral_data.h"

namespace kasha {

struct BispectralChannel {
  float lambdaIn = 0.0f;                // nm
  std::optional<float> lambdaOut;       // nm; empty for a diagonal channel
};
// Parses a channel name; empty for a name that is not a reflective or reradiation channel.
std::optional<BispectralChannel> parseBispectralChannel(const std::string& name);

// Throws InputError naming the file (and channel) if it cannot be read, has no T.* channel, or a
// reradiation pair whose wavelengths are not on the grid of the others.
BispectralData readBispectralExr(const std::string& path);
// One-pixel file: a "T.<λ>nm" channel wherever λ is both an input and an output wavelength, and a
// "T.<λ_i>nm.<λ_o>nm" channel for every other cell.
void writeBispectralExr(const std::string& path, const BispectralData& d);

}  // namespace kasha
