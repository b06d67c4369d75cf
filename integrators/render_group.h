#pragma once
// The processes that render one image together (MPI ranks, cli/mpi_group.h). The render loop
// (render_loop.h) deals the passes round-robin: in each round rank r traces the r-th pass, every
// other rank sends its PassRecord to rank 0, and rank 0 commits the round's records in pass
// order, so its film holds exactly the sums of a one-process render. All decisions that end a
// render (a stop request on any rank, rank 0's time budget) are agreed on collectively after the
// same round, so every rank stops at the same pass. Before all that, rank 0 checks that every rank
// renders the same image (rank_agreement.h).
#include <cstddef>
#include <span>

#include "integrators/render_pass.h"

namespace kasha {

class RenderGroup {
 public:
  virtual ~RenderGroup() = default;
  // This process's index in [0, size()); rank 0 holds the film that is written.
  virtual int rank() const = 0;
  virtual int size() const = 0;
  // A rank other than 0: sends the record of the pass it traced to rank 0.
  virtual void send(const PassRecord& record) = 0;
  // Rank 0: receives the record `from` traced in this round. Throws std::runtime_error if it
  // does not describe a pass of a width × height film.
  virtual PassRecord receive(int from, int width, int height) = 0;
  // Every rank, collectively: replaces each value by its maximum over the ranks.
  virtual void maxOverRanks(std::span<int> values) = 0;
  // Every rank, collectively, with `mine` of the same size on every rank: rank 0 receives rank
  // r's bytes at all[r·mine.size()] (all holds size()·mine.size() bytes there; elsewhere it is
  // not used). Only rank 0 waits for the others.
  virtual void gatherToRoot(std::span<const std::byte> mine, std::span<std::byte> all) = 0;
};

}  // namespace kasha
