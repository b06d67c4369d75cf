#include "core/sensor_sampling.h"

#include <algorithm>
#include <stdexcept>

#include "core/color.h"

namespace kasha {

SensorSampling parseSensorSampling(const std::string& name) {
  if (name == "uniform") return SensorSampling::Uniform;
  if (name == "cmf") return SensorSampling::ColorMatching;
  throw std::invalid_argument("unknown sensor wavelength sampling '" + name + "' (uniform | cmf)");
}

const char* toString(SensorSampling s) { return s == SensorSampling::Uniform ? "uniform" : "cmf"; }

SensorWavelengths::SensorWavelengths(SensorSampling mode, WavelengthRange scene) : mode_(mode) {
  // The observer is zero outside 360–830 nm, so no sample is spent there.
  const WavelengthRange seen{std::max(scene.min, 360.0f), std::min(scene.max, 830.0f)};
  if (mode == SensorSampling::Uniform) {
    dist_ = SpectralDistribution(Spectrum::constant(1.0f), seen);
  } else {
    const Observer& o = Observer::cie1931();
    std::vector<float> x, y;
    for (float l : o.ybar.lambdas()) {
      x.push_back(l);
      y.push_back(o.xbar(l) + o.ybar(l) + o.zbar(l));
    }
    dist_ = SpectralDistribution(Spectrum::piecewiseLinear(x, y), seen);
  }
}

}  // namespace kasha
