#include "cli/mpi_group.h"

#include <mpi.h>

#include <algorithm>
#include <array>
#include <cstdlib>
#include <stdexcept>
#include <string>

namespace kasha {
namespace {

constexpr int kHeaderTag = 1, kDataTag = 2;
// MPI counts are ints: large buffers go in pieces of at most 1 GiB.
constexpr size_t kChunk = size_t(1) << 30;

template <class T>
void sendVector(const std::vector<T>& v, int to) {
  const auto* bytes = reinterpret_cast<const char*>(v.data());
  const size_t n = v.size() * sizeof(T);
  for (size_t off = 0; off < n; off += kChunk)
    MPI_Send(bytes + off, int(std::min(kChunk, n - off)), MPI_BYTE, to, kDataTag, MPI_COMM_WORLD);
}

template <class T>
void receiveVector(std::vector<T>& v, uint64_t count, int from) {
  v.resize(size_t(count));
  auto* bytes = reinterpret_cast<char*>(v.data());
  const size_t n = v.size() * sizeof(T);
  for (size_t off = 0; off < n; off += kChunk)
    MPI_Recv(bytes + off, int(std::min(kChunk, n - off)), MPI_BYTE, from, kDataTag, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
}

}  // namespace

bool launchedByMpi() {
  for (const char* var : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMIX_RANK"})
    if (std::getenv(var)) return true;
  return false;
}

MpiGroup::MpiGroup(int* argc, char*** argv) {
  int provided = 0;
  MPI_Init_thread(argc, argv, MPI_THREAD_FUNNELED, &provided);
  MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
  MPI_Comm_size(MPI_COMM_WORLD, &size_);
}

MpiGroup::~MpiGroup() { MPI_Finalize(); }

// A record goes as a header (pass, sizes, ray counts) followed by its five arrays as bytes:
// every rank runs the same binary on the same kind of machine.
void MpiGroup::send(const PassRecord& r) {
  const std::array<uint64_t, 9> header{uint64_t(r.first), uint64_t(r.count), r.samples.size(), r.splats.size(),
                                       r.strategies.size(), r.rays.closest, r.rays.shadow, r.spectralCounts.size(),
                                       r.spectral.size()};
  MPI_Send(header.data(), int(header.size()), MPI_UINT64_T, 0, kHeaderTag, MPI_COMM_WORLD);
  sendVector(r.samples, 0);
  sendVector(r.splats, 0);
  sendVector(r.strategies, 0);
  sendVector(r.spectralCounts, 0);
  sendVector(r.spectral, 0);
}

PassRecord MpiGroup::receive(int from, int width, int height) {
  std::array<uint64_t, 9> header{};
  MPI_Recv(header.data(), int(header.size()), MPI_UINT64_T, from, kHeaderTag, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
  PassRecord r;
  r.first = int(header[0]);
  r.count = int(header[1]);
  if (header[1] == 0 || header[2] != uint64_t(width) * uint64_t(height) * header[1])
    throw std::runtime_error("MPI rank " + std::to_string(from) + " sent a pass of " + std::to_string(header[2]) +
                             " samples, not one for a " + std::to_string(width) + "x" + std::to_string(height) + " film");
  receiveVector(r.samples, header[2], from);
  receiveVector(r.splats, header[3], from);
  receiveVector(r.strategies, header[4], from);
  if (header[7] != 0 && header[7] != header[2])
    throw std::runtime_error("MPI rank " + std::to_string(from) + " sent spectral counts for " + std::to_string(header[7]) +
                             " samples in a pass of " + std::to_string(header[2]));
  receiveVector(r.spectralCounts, header[7], from);
  receiveVector(r.spectral, header[8], from);
  uint64_t shares = 0;
  for (const uint32_t n : r.spectralCounts) shares += n;
  if (shares != header[8])
    throw std::runtime_error("MPI rank " + std::to_string(from) + " sent " + std::to_string(header[8]) +
                             " spectral shares, but its counts add up to " + std::to_string(shares));
  r.rays = RayCounter{header[5], header[6]};
  return r;
}

void MpiGroup::maxOverRanks(std::span<int> values) {
  MPI_Allreduce(MPI_IN_PLACE, values.data(), int(values.size()), MPI_INT, MPI_MAX, MPI_COMM_WORLD);
}

void MpiGroup::gatherToRoot(std::span<const std::byte> mine, std::span<std::byte> all) {
  MPI_Gather(mine.data(), int(mine.size()), MPI_BYTE, rank_ == 0 ? all.data() : nullptr, int(mine.size()), MPI_BYTE, 0,
             MPI_COMM_WORLD);
}

void MpiGroup::barrier() { MPI_Barrier(MPI_COMM_WORLD); }

void MpiGroup::abort(int code) {
  MPI_Abort(MPI_COMM_WORLD, code);
  std::exit(code);  // MPI_Abort does not return; this satisfies [[noreturn]] if it ever did
}

}  // namespace kasha
