#pragma once
// The photons of one pass with FLANN's single k-d tree over their positions (flann::Index with
// KDTreeSingleIndexParams), built once and then queried from many threads.
#include <memory>
#include <vector>

#include "core/math.h"
#include "integrators/photon_mapping/photon.h"

namespace flann {
template <class T>
struct L2_Simple;
template <typename Distance>
class Index;
}  // namespace flann

namespace kasha {

class PhotonMap {
 public:
  explicit PhotonMap(std::vector<Photon> photons);
  ~PhotonMap();
  PhotonMap(const PhotonMap&) = delete;
  PhotonMap& operator=(const PhotonMap&) = delete;

  // Indices of the photons at distance < radius from p, in no particular order (FLANN's
  // radiusSearch). The vector belongs to the calling thread and is overwritten by its next query.
  const std::vector<size_t>& within(const Vec3& p, float radius) const;
  const Photon& operator[](size_t i) const { return photons_[i]; }
  size_t size() const { return photons_.size(); }
  // FLANN's own count of the memory its tree uses (node pool and permutation array).
  size_t treeBytes() const;

 private:
  std::vector<Photon> photons_;
  std::unique_ptr<flann::Index<flann::L2_Simple<float>>> index_;  // null when there are no photons
};

}  // namespace kasha
