#pragma once
// The throughput of a camera path's wavelength lanes kept apart per sensor wavelength of the camera
// sample: component j is the share that reaches the sensor at the sample's j-th wavelength, so
// every contribution goes through sensorResponse at the wavelength the sensor sees (spectral bins
// stay exact) even where a fluorescent event mixes the lanes (laneWeight sums over them). Photon
// mapping's camera paths carry it always, the path tracer's when the render keeps spectral bins
// (otherwise an XYZ 3-vector). It has the operations laneWeight and laneNextEvent need.
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
  SensorShares& operator/=(float s) {
    for (float& x : v) x /= s;
    return *this;
  }
  float sum() const {
    float s = 0.0f;
    for (const float x : v) s += x;
    return s;
  }
  bool operator==(const SensorShares&) const = default;
  bool anyPositive() const {
    for (const float x : v)
      if (x > 0.0f) return true;
    return false;
  }
};

// The lane's magnitude (wavelength_lanes.h): the sum of its shares.
inline float magnitude(const SensorShares& beta) { return beta.sum(); }

using CameraLanes = PathLanes<SensorShares>;

}  // namespace kasha
