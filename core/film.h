#pragma once
// The film: per-pixel sums of XYZ estimates. Non-finite samples never reach it; they are counted
// with the first pixel that produced one, so that a bug can be found.
#include <atomic>
#include <cstdint>
#include <mutex>
#include <utility>
#include <vector>

#include "core/math.h"

namespace kasha {

struct DVec3 {
  double x = 0.0, y = 0.0, z = 0.0;
};

class Film {
 public:
  Film(int width, int height) : w_(width), h_(height), sum_(size_t(width) * height), splat_(size_t(width) * height) {}

  // Bytes a film of this size allocates (the two sum buffers), to check a memory limit before
  // constructing one.
  static uint64_t bytesFor(int width, int height) { return uint64_t(width) * uint64_t(height) * 2 * sizeof(DVec3); }

  // Not thread-safe per pixel: each pixel is written by one task at a time.
  void add(int x, int y, const Vec3& xyz) { accumulate(sum_, x, y, xyz); }
  // Splats from light paths: summed separately, divided by the same samples per pixel.
  void addSplat(int x, int y, const Vec3& xyz) { accumulate(splat_, x, y, xyz); }
  // Counts a sample that could not be added at all (a splat at a non-finite position: pixel -1, -1).
  void addNonFinite(int x, int y) { recordNonFinite(x, y); }
  void setSamplesPerPixel(int spp) { spp_ = spp; }
  int samplesPerPixel() const { return spp_; }
  int width() const { return w_; }
  int height() const { return h_; }
  // The estimate of a pixel: sum / spp.
  Vec3 xyz(int x, int y) const;
  // Mean XYZ over the whole image.
  DVec3 meanXyz() const;
  uint64_t nonFiniteCount() const { return nonFinite_.load(); }
  std::pair<int, int> firstNonFinitePixel() const { return firstBad_; }

  // The raw state, for checkpoints (core/checkpoint.h): per-pixel sums of camera samples and of
  // splats, row-major.
  const std::vector<DVec3>& sampleSums() const { return sum_; }
  const std::vector<DVec3>& splatSums() const { return splat_; }
  // Replaces the whole state by a checkpoint's. Both buffers must have width × height entries.
  void restore(std::vector<DVec3> sums, std::vector<DVec3> splats, int spp, uint64_t nonFinite,
               std::pair<int, int> firstNonFinite);

 private:
  void accumulate(std::vector<DVec3>& buffer, int x, int y, const Vec3& xyz) {
    if (!std::isfinite(xyz.x) || !std::isfinite(xyz.y) || !std::isfinite(xyz.z)) {
      recordNonFinite(x, y);
      return;
    }
    DVec3& s = buffer[size_t(y) * w_ + x];
    s.x += xyz.x, s.y += xyz.y, s.z += xyz.z;
  }
  void recordNonFinite(int x, int y);
  int w_, h_, spp_ = 0;
  std::vector<DVec3> sum_, splat_;
  std::atomic<uint64_t> nonFinite_{0};
  std::mutex badMutex_;
  std::pair<int, int> firstBad_{-1, -1};
};

}  // namespace kasha
