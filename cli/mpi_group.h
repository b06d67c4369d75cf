#pragma once
// The ranks of an MPI job (Open MPI) as a RenderGroup (integrators/render_group.h): `mpirun -np N
// kasha render ...` renders one image with N processes, bit-identical to one process.
#include "integrators/render_group.h"

namespace kasha {

// True if this process was started by an MPI launcher (Open MPI's mpirun/mpiexec, or a PMI or
// PMIx launcher such as Slurm's srun), judged by the environment it sets.
bool launchedByMpi();

class MpiGroup final : public RenderGroup {
 public:
  // Initialises MPI (only the calling thread will make MPI calls); finalises it when destroyed.
  MpiGroup(int* argc, char*** argv);
  ~MpiGroup() override;
  MpiGroup(const MpiGroup&) = delete;
  MpiGroup& operator=(const MpiGroup&) = delete;

  int rank() const override { return rank_; }
  int size() const override { return size_; }
  void send(const PassRecord& record) override;
  PassRecord receive(int from, int width, int height) override;
  void maxOverRanks(std::span<int> values) override;
  void gatherToRoot(std::span<const std::byte> mine, std::span<std::byte> all) override;
  // Returns when every rank has called it.
  void barrier();
  // Ends every rank of the job with exit code `code` (after an error on this rank that the
  // others, waiting for it, would never see).
  [[noreturn]] void abort(int code);

 private:
  int rank_ = 0, size_ = 1;
};

}  // namespace kasha
