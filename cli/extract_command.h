#pragma once
// `kasha extract`: Zhdanov et al.'s extraction (materials/zhdanov_extraction.h) from bispectral
// measurements to a loadable three-part material. Writes <output>.json (a material object, usable
// in a scene as {"type": "file", "file": "<output>.json"} or pasted into "materials") and
// <output stem>_spectra.csv (p, A, E on the union of the input and output grids, zero outside
// each one's own grid), and prints the factorisation residual.
#include <string>

namespace kasha {

struct ExtractArgs {
  std::string sample, etalon, etalonReflectance, output;
  float epsilon = 5.0f;
  float noiseFloor = 0.002f;
  float gloss = 0.0f;
  float glossExponent = 100.0f;
};

// Returns the exit code; throws InputError on bad input.
int runExtract(const ExtractArgs& args);

}  // namespace kasha
