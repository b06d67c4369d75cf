#pragma once
// Spectra in scene files. A spectrum is written as
//   0.5                                  constant
//   "D65"  or  "my_name"                 a preset, or an entry of the scene's "spectra" section
//   {"type": "constant", "value": v}
//   {"type": "tabulated", "wavelengths": [...], "values": [...]}
//   {"type": "file", "file": "x.csv", "column": "name", "outside": "clamp" | "zero"}
//     (a file that does not cover the scene's wavelength range needs an explicit "outside")
//   {"type": "gaussian", "center": nm, "fwhm": nm, "peak": v}
//   {"type": "blackbody", "kelvin": T}
//   {"type": "box", "min": nm, "max": nm, "value": v}
//   {"type": "rgb", "value": [r, g, b]}  a reflectance from a linear sRGB colour (rgb_spectrum.h)
//   {"type": "preset", "name": "D65"}
// and every object form takes an optional "scale". Files are relative to the scene file.
#include <functional>
#include <map>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/memory_budget.h"
#include "core/spectrum.h"

namespace kasha {

class TextureLoader;

struct SpectrumContext {
  SpectrumContext() = default;
  SpectrumContext(std::string sceneFile, std::string dir, const std::map<std::string, Spectrum>* names = nullptr)
      : file(std::move(sceneFile)), baseDir(std::move(dir)), named(names) {}

  std::string file;     // the scene file, for messages
  std::string baseDir;  // directory that relative paths start from
  // A file named in the scene: absolute as it is, else relative to baseDir.
  std::string resolve(const std::string& rel) const { return !rel.empty() && rel[0] == '/' ? rel : baseDir + "/" + rel; }
  const std::map<std::string, Spectrum>* named = nullptr;
  // If set, resolves a name (before `named` and the presets): the scene loader parses named
  // spectra on demand with it. Returns nullptr for an unknown name; `pointer` is where the name
  // is used, for messages.
  std::function<const Spectrum*(const std::string& name, const std::string& pointer)> resolveName;
  // If set, the scene's wavelength range: a spectrum file must cover it, or say with "outside"
  // how to extend it, and must overlap it.
  const WavelengthRange* range = nullptr;
  // If set, loads the textures of materials (core/texture.h) against the scene's memory limit;
  // otherwise each texture is loaded on its own against the default limit.
  TextureLoader* textures = nullptr;
  // The largest buffer a file named in the scene may need (a decoded texture).
  uint64_t memoryLimit = kDefaultMemoryLimit;
  // The material files (type "file") being read, outermost first: a file that names one of them
  // is a cycle, and the chain has a depth limit.
  std::vector<std::string> materialFiles;
};

Spectrum parseSpectrum(const nlohmann::json& v, const SpectrumContext& ctx, const std::string& pointer);

}  // namespace kasha
