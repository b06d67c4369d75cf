#pragma once
// How the camera chooses the wavelength of a path: uniformly over the part of the scene's range
// the observer sees, or in proportion to x̄ + ȳ + z̄ (fewer samples where the eye is blind).
#include <string>

#include "core/spectral_distribution.h"

namespace kasha {

enum class SensorSampling { Uniform, ColorMatching };

SensorSampling parseSensorSampling(const std::string& name);  // "uniform" | "cmf"
const char* toString(SensorSampling s);

class SensorWavelengths {
 public:
  SensorWavelengths(SensorSampling mode, WavelengthRange sceneRange);
  WavelengthSample sample(float u) const { return dist_.sample(u); }
  float pdf(float lambda) const { return dist_.pdf(lambda); }
  SensorSampling mode() const { return mode_; }

 private:
  SensorSampling mode_;
  SpectralDistribution dist_;
};

}  // namespace kasha
