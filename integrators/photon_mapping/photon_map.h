#pragma once
// The photons of one pass with FLANN's single k-d trees over their positions
// (flann::KDTreeSingleIndex), built once and then queried from many threads. FLANN builds a tree on
// one thread, so a large map is first split at the median of its longest axis into kCells cells
// (three levels: 8 cells) whose trees are built in parallel; a query searches the cells its ball
// reaches. The split depends on the photons only, never on the number of threads.
#include <memory>
#include <vector>

#include "core/math.h"
#include "integrators/photon_mapping/photon.h"

namespace flann {
template <class T>
struct L2_Simple;
template <typename Distance>
class KDTreeSingleIndex;
}  // namespace flann

namespace kasha {

class PhotonMap {
 public:
  // Maps with fewer photons than this keep one tree (one cell).
  static constexpr size_t kSplitFrom = 4096;
  static constexpr int kSplitLevels = 3;

  // Reorders the photons by cell.
  explicit PhotonMap(std::vector<Photon> photons);
  ~PhotonMap();
  PhotonMap(const PhotonMap&) = delete;
  PhotonMap& operator=(const PhotonMap&) = delete;

  // Indices (for operator[]) of the photons at distance < radius from p, in no particular order
  // (FLANN's search in each cell the ball reaches, reported straight into the vector: no
  // per-query buffers, no distances). The vector belongs to the calling thread
  // and is overwritten by its next query.
  const std::vector<size_t>& within(const Vec3& p, float radius) const;
  const Photon& operator[](size_t i) const { return photons_[i]; }
  size_t size() const { return photons_.size(); }
  size_t cells() const { return cells_.size(); }
  // FLANN's own count of the memory its trees use (node pools and permutation arrays).
  size_t treeBytes() const;

 private:
  struct Cell {
    size_t begin = 0, end = 0;  // its photons: photons_[begin, end)
    Vec3 lo{0.0f}, hi{0.0f};    // their bounding box
    std::unique_ptr<flann::KDTreeSingleIndex<flann::L2_Simple<float>>> index;  // null for an empty cell
  };
  std::vector<Photon> photons_;
  std::vector<Cell> cells_;
};

}  // namespace kasha
