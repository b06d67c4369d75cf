#pragma once
// Records with a position (`float p[3]`, their first member) and FLANN's single k-d trees over those
// positions (flann::KDTreeSingleIndex), built once and then queried from many threads: photon
// mapping's photons and vertex merging's light vertices. FLANN builds a tree on one thread, so a
// large map is first split at the median of its longest axis into cells (three levels: 8 cells)
// whose trees are built in parallel; a query searches the cells its ball reaches. The split depends
// on the records only, never on the number of threads. The definitions are in point_map_impl.h, for
// the files that instantiate a map.
#include <memory>
#include <vector>

#include "core/math.h"

namespace flann {
template <class T>
struct L2_Simple;
template <typename Distance>
class KDTreeSingleIndex;
}  // namespace flann

namespace kasha {

// Leaf size of the k-d trees (KDTreeSingleIndexParams).
inline constexpr int kPointLeafSize = 24;

template <class Record>
class PointMap {
 public:
  // Maps with fewer records than this keep one tree (one cell).
  static constexpr size_t kSplitFrom = 4096;
  static constexpr int kSplitLevels = 3;

  // Reorders the records by cell.
  explicit PointMap(std::vector<Record> records);
  ~PointMap();
  PointMap(const PointMap&) = delete;
  PointMap& operator=(const PointMap&) = delete;

  // Indices (for operator[]) of the records at distance < radius from p, in no particular order
  // (FLANN's search in each cell the ball reaches, reported straight into the vector: no
  // per-query buffers, no distances). The vector belongs to the calling thread
  // and is overwritten by its next query.
  const std::vector<size_t>& within(const Vec3& p, float radius) const;
  const Record& operator[](size_t i) const { return records_[i]; }
  size_t size() const { return records_.size(); }
  size_t cells() const { return cells_.size(); }
  // FLANN's own count of the memory its trees use (node pools and permutation arrays).
  size_t treeBytes() const;

 private:
  struct Cell {
    size_t begin = 0, end = 0;  // its records: records_[begin, end)
    Vec3 lo{0.0f}, hi{0.0f};    // their bounding box
    std::unique_ptr<flann::KDTreeSingleIndex<flann::L2_Simple<float>>> index;  // null for an empty cell
  };
  std::vector<Record> records_;
  std::vector<Cell> cells_;
};

}  // namespace kasha
