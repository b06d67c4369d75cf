#pragma once
// Emissive spectral images in the OpenEXR layout of Fichet, Pacanowski & Wilkie (2021), "An
// OpenEXR Layout for Spectral Images", JCGT 10(3), §3: one channel "S0.<λ>" per wavelength (the
// first Stokes component, i.e. unpolarised radiance; λ with a decimal comma and a unit,
// core/exr_wavelength.h), the header attributes spectralLayoutVersion = "1.0" and emissiveUnits =
// "W.m^-2.sr^-1" (radiance per nm: the unit of the wavelength the channel names). kasha writes the
// bins of a SpectralFilm at their centres beside its R, G, B and XYZ layers (core/image_output.h).
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "core/image_input.h"
#include "core/spectral_film.h"

namespace kasha {

// "S0.<λ>nm" for a bin centred at λ.
std::string emissiveChannelName(float nm);
// The layout's string attributes (name, value) for the header of a spectral image.
std::vector<std::pair<std::string, std::string>> spectralAttributes();
// One (name, row-major float image) pair per bin of the film: its radiance per nm.
std::vector<std::pair<std::string, std::vector<float>>> spectralChannels(const SpectralFilm& film);

struct SpectralImage {
  int width = 0, height = 0;
  std::vector<float> wavelengths;  // the channels' wavelengths in nm, increasing
  std::vector<float> values;       // pixel-major: values[(y·width + x)·wavelengths.size() + k]
  float at(int x, int y, size_t k) const { return values[(size_t(y) * width + x) * wavelengths.size() + k]; }
};

class ExrInput;  // core/exr_input.h

// True if the opened file has at least one S0.<λ> channel.
bool hasEmissiveChannels(ExrInput& in);
// Reads every S0.<λ> channel, opening the file by core/input_file.h's rule. Throws InputError naming
// the file (and channel) if it cannot be read, has none, names one wavelength twice, declares more
// pixels and channels than `memoryLimit` allows, or holds a non-finite value.
SpectralImage readSpectralExr(const std::string& path, uint64_t memoryLimit = kDefaultMemoryLimit);
// The same from a file already opened as `path`.
SpectralImage readSpectralExr(ExrInput& in, const std::string& path, uint64_t memoryLimit);

// A render or spectral image read back with one read of the file: its XYZ (as readExrXyz) and its
// S0.<λ> channels (no wavelengths if it has none).
struct ExrImage {
  XyzImage xyz;
  SpectralImage spectral;
};
ExrImage readExrImage(const std::string& path, uint64_t memoryLimit = kDefaultMemoryLimit);
// XYZ in the film's normalisation (core/color.h): each channel is the mean radiance per nm of the
// band from the midpoint with its lower neighbour to the midpoint with its upper one (the end
// bands symmetric about their centre), integrated exactly against the CIE 1931 observer.
XyzImage spectralToXyz(const SpectralImage& image);

}  // namespace kasha
