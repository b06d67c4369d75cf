#pragma once
// The throughput type of photon mapping's camera lanes: a lane's weight kept apart per sensor
// wavelength of the camera sample. Component j is the share that reaches the sensor at the sample's
// j-th wavelength, so every contribution goes through sensorResponse at the wavelength the sensor
// sees (spectral bins stay exact) even where a fluorescent event mixes the lanes (laneWeight sums
// over them). It has the operations laneWeight and laneNextEvent need.
#include "integrators/wavelength_lanes.h"

namespace kasha {

struct SensorShares {
  float v[kMaxLanes] = {};

  SensorShares operator*(float s) const {
    SensorShares r;
    for (int j = 0; j < kMaxLanes; ++j) r.v[j] = v[j] * s;
    return r;
  }
  SensorShares& operator+=(const SensorShares& o) {
    for (int j = 0; j < kMaxLanes; ++j) v[j] += o.v[j];
    return *this;
  }
  bool anyPositive() const {
    for (const float x : v)
      if (x > 0.0f) return true;
    return false;
  }
};

// The lanes of a camera path segment: wavelength and throughput (over the path density) of each.
struct CameraLanes {
  int n = 0;
  float lambda[kMaxLanes];
  SensorShares T[kMaxLanes];
};

}  // namespace kasha
