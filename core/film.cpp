#include "core/film.h"

#include <stdexcept>

namespace kasha {

Vec3 Film::xyz(int x, int y) const {
  if (spp_ == 0) return Vec3(0.0f);
  const DVec3& s = sum_[size_t(y) * w_ + x];
  const DVec3& p = splat_[size_t(y) * w_ + x];
  return Vec3(float((s.x + p.x) / spp_), float((s.y + p.y) / spp_), float((s.z + p.z) / spp_));
}

DVec3 Film::meanXyz() const {
  DVec3 m;
  if (spp_ == 0) return m;
  const double n = double(sum_.size()) * spp_;
  for (const DVec3& s : sum_) m.x += s.x / n, m.y += s.y / n, m.z += s.z / n;
  for (const DVec3& s : splat_) m.x += s.x / n, m.y += s.y / n, m.z += s.z / n;
  return m;
}

void Film::restore(std::vector<DVec3> sums, std::vector<DVec3> splats, int spp, uint64_t nonFinite,
                   std::pair<int, int> firstNonFinite) {
  if (sums.size() != sum_.size() || splats.size() != splat_.size())
    throw std::invalid_argument("Film::restore: buffer size does not match the film");
  sum_ = std::move(sums);
  splat_ = std::move(splats);
  spp_ = spp;
  nonFinite_.store(nonFinite);
  firstBad_ = firstNonFinite;
}

void Film::recordNonFinite(int x, int y) {
  if (nonFinite_.fetch_add(1) == 0) {
    std::lock_guard<std::mutex> lock(badMutex_);
    firstBad_ = {x, y};
  }
}

}  // namespace kasha
