#pragma once
// Spectra in scene files. A spectrum is written as
//   0.5                                  constant
//   "D65"  or  "my_name"                 a preset, or an entry of the scene's "spectra" section
//   {"type": "constant", "value": v}
//   {"type": "tabulated", "wavelengths": [...], "values": [...]}
//   {"type": "file", "file": "x.csv", "column": "name", "outside": "clamp" | "zero"}
//   {"type": "gaussian", "center": nm, "fwhm": nm, "peak": v}
//   {"type": "blackbody", "kelvin": T}
//   {"type": "box", "min": nm, "max": nm, "value": v}
//   {"type": "preset", "name": "D65"}
// and every object form takes an optional "scale". Files are relative to the scene file.
#include <map>
#include <string>

#include <nlohmann/json.hpp>

#include "core/spectrum.h"

namespace kasha {

struct SpectrumContext {
  std::string file;     // the scene file, for messages
  std::string baseDir;  // directory that relative paths start from
  const std::map<std::string, Spectrum>* named = nullptr;
};

Spectrum parseSpectrum(const nlohmann::json& v, const SpectrumContext& ctx, const std::string& pointer);

}  // namespace kasha
