#pragma once
// PointMap's definitions (point_map.h), included by the files that instantiate a map.
#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>

#include <algorithm>
#include <flann/flann.hpp>

#include "integrators/point_map.h"

namespace kasha {
namespace point_map_detail {

template <class Record>
Vec3 position(const Record& r) { return Vec3(r.p[0], r.p[1], r.p[2]); }

// Splits records[begin, end) at the median of the longest axis of their bounding box, `levels`
// times; cell `first` + k receives the k-th of the 2^levels parts (in order along the splits).
template <class Record>
void split(std::vector<Record>& records, size_t begin, size_t end, int levels, size_t first, std::vector<size_t>& bounds) {
  if (levels == 0) {
    bounds[first + 1] = end;
    return;
  }
  if (end - begin > 1) {
    Vec3 lo(kInf), hi(-kInf);
    for (size_t i = begin; i < end; ++i) {
      lo = glm::min(lo, position(records[i]));
      hi = glm::max(hi, position(records[i]));
    }
    const Vec3 extent = hi - lo;
    const int axis = extent.x >= extent.y && extent.x >= extent.z ? 0 : extent.y >= extent.z ? 1 : 2;
    std::nth_element(records.begin() + long(begin), records.begin() + long(begin + (end - begin) / 2),
                     records.begin() + long(end),
                     [axis](const Record& a, const Record& b) { return a.p[axis] < b.p[axis]; });
  }
  const size_t mid = begin + (end - begin) / 2;
  const size_t half = size_t(1) << (levels - 1);
  tbb::parallel_invoke([&] { split(records, begin, mid, levels - 1, first, bounds); },
                       [&] { split(records, mid, end, levels - 1, first + half, bounds); });
}

// Hands FLANN's search results (indices within a cell) to the map's order, as a radius search's
// result set does (flann::RadiusResultSet: never full, the radius as the worst distance, which the
// tree's leaves compare with before adding), without storing distances.
class CollectWithin final : public flann::ResultSet<float> {
 public:
  CollectWithin(std::vector<size_t>& found, size_t offset, float r2) : found_(found), offset_(offset), r2_(r2) {}
  bool full() const override { return true; }
  void addPoint(float, size_t index) override { found_.push_back(offset_ + index); }
  float worstDist() const override { return r2_; }

 private:
  std::vector<size_t>& found_;
  size_t offset_;
  float r2_;
};

}  // namespace point_map_detail

template <class Record>
PointMap<Record>::PointMap(std::vector<Record> records) : records_(std::move(records)) {
  const int levels = records_.size() >= kSplitFrom ? kSplitLevels : 0;
  std::vector<size_t> bounds((size_t(1) << levels) + 1, 0);
  point_map_detail::split(records_, 0, records_.size(), levels, 0, bounds);
  cells_.resize(size_t(1) << levels);
  tbb::parallel_for(size_t(0), cells_.size(), [&](size_t c) {
    Cell& cell = cells_[c];
    cell.begin = bounds[c];
    cell.end = bounds[c + 1];
    if (cell.begin == cell.end) return;
    cell.lo = cell.hi = point_map_detail::position(records_[cell.begin]);
    for (size_t i = cell.begin; i < cell.end; ++i) {
      cell.lo = glm::min(cell.lo, point_map_detail::position(records_[i]));
      cell.hi = glm::max(cell.hi, point_map_detail::position(records_[i]));
    }
    // Rows are the records' positions, read in place: sizeof(Record) bytes apart.
    const flann::Matrix<float> positions(const_cast<float*>(records_[cell.begin].p), cell.end - cell.begin, 3, sizeof(Record));
    cell.index = std::make_unique<flann::KDTreeSingleIndex<flann::L2_Simple<float>>>(
        positions, flann::KDTreeSingleIndexParams(kPointLeafSize));
    cell.index->buildIndex();
  });
}

template <class Record>
PointMap<Record>::~PointMap() = default;

template <class Record>
const std::vector<size_t>& PointMap<Record>::within(const Vec3& p, float radius) const {
  thread_local std::vector<size_t> found;
  found.clear();
  float q[3] = {p.x, p.y, p.z};
  const flann::SearchParams params;  // eps = 0: exact
  const float r2 = radius * radius;
  for (const Cell& cell : cells_) {
    if (!cell.index) continue;
    const Vec3 d = glm::max(glm::max(cell.lo - p, p - cell.hi), Vec3(0.0f));  // to the cell's box
    if (glm::dot(d, d) >= r2) continue;
    // L2_Simple measures squared distances, so the search radius is r².
    point_map_detail::CollectWithin collect(found, cell.begin, r2);
    cell.index->findNeighbors(collect, q, params);
  }
  return found;
}

template <class Record>
size_t PointMap<Record>::treeBytes() const {
  size_t bytes = 0;
  for (const Cell& cell : cells_)
    if (cell.index) bytes += size_t(cell.index->usedMemory());
  return bytes;
}

}  // namespace kasha
