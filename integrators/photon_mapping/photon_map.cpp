#include "integrators/photon_mapping/photon_map.h"

#include <flann/flann.hpp>

namespace kasha {

PhotonMap::PhotonMap(std::vector<Photon> photons) : photons_(std::move(photons)) {
  if (photons_.empty()) return;
  // Rows are the photons' positions, read in place: sizeof(Photon) bytes apart.
  const flann::Matrix<float> positions(photons_[0].p, photons_.size(), 3, sizeof(Photon));
  index_ = std::make_unique<flann::Index<flann::L2_Simple<float>>>(positions,
                                                                   flann::KDTreeSingleIndexParams(kPhotonLeafSize));
  index_->buildIndex();
}

PhotonMap::~PhotonMap() = default;

const std::vector<size_t>& PhotonMap::within(const Vec3& p, float radius) const {
  thread_local std::vector<std::vector<size_t>> indices(1);
  thread_local std::vector<std::vector<float>> dists(1);
  indices[0].clear();
  if (!index_) return indices[0];
  float q[3] = {p.x, p.y, p.z};
  flann::SearchParams params;
  params.sorted = false;  // every photon in the disc counts; the order does not matter
  // L2_Simple measures squared distances, so the search radius is r².
  index_->radiusSearch(flann::Matrix<float>(q, 1, 3), indices, dists, radius * radius, params);
  return indices[0];
}

size_t PhotonMap::treeBytes() const { return index_ ? size_t(index_->usedMemory()) : 0; }

}  // namespace kasha
