#pragma once
// Mitsuba spectra as kasha spectrum JSON (docs/scene-format.md "Spectra"): <spectrum value="0.5">,
// <spectrum value="400:0.1, 500:0.3">, <spectrum filename="x.spd"> (Mitsuba's two-column text
// files), <spectrum type="uniform|regular|irregular|blackbody">, <blackbody temperature="..">
// and <float>, and <rgb> colours: upsampled by Jakob & Hanika 2019 (core/rgb_spectrum.h) as
// reflectances, and as emission spectra by core/rgb_illuminant.h. As a kasha extension,
// filename="x.csv" with column="name" reads a kasha CSV spectrum file. Textures are refused.
#include <nlohmann/json.hpp>

#include "scene/mitsuba/xml_plugin.h"

namespace kasha::mitsuba {

// What a spectrum describes: it decides how an <rgb> colour is upsampled.
enum class SpectrumUse { Reflectance, Emission };

// The spectrum property `name` of `owner` as kasha JSON; `fallback` if it is absent (a null
// fallback makes it required).
nlohmann::json spectrumProperty(Plugin& owner, const std::string& name, const nlohmann::json& fallback = nullptr,
                                SpectrumUse use = SpectrumUse::Reflectance);
// The same for an element already found (a <spectrum>, <float>, <blackbody>, <rgb>, ...).
nlohmann::json spectrumElement(XmlImport& xml, pugi::xml_node p, SpectrumUse use = SpectrumUse::Reflectance);

// Planck's spectral radiance of a black body at `kelvin`, in W·m⁻²·sr⁻¹·nm⁻¹ at `nm`.
double planckRadiance(double nm, double kelvin);

}  // namespace kasha::mitsuba
