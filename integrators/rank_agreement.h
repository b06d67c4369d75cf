#pragma once
// Ranks that disagree (docs/mpi.md): before the processes of a RenderGroup exchange anything else,
// rank 0 compares, field by field, what each of them is about to render — a record of everything
// that determines the image: the job's settings as a checkpoint records them (the scene's hash,
// the integrator and every setting of its estimator, seed, resolution, spectral bins;
// RenderJob::checkpointSettings) and the render loop's own (spp, time budget, samples per pass,
// where a resumed render starts). Without it a rank given another --spp waits for passes that never
// come, and one given another seed, scene or integrator adds its samples to a mixed image.
//
// Each field travels as a fixed-size digest (its name, the start of its value's text and the
// value's hashBytes), and every rank sends the same number of bytes whatever its record holds, so
// a difference is reported, never a deadlock.
#include <array>
#include <cstdint>
#include <string>
#include <type_traits>

#include <nlohmann/json.hpp>

#include "core/error.h"
#include "integrators/render_group.h"

namespace kasha {

struct RecordDigest {
  static constexpr int kFields = 64;
  struct Field {
    char name[32];   // "seed", "ppm.direct": the record's key, nested objects' keys joined by '.'
    char value[88];  // the value as JSON text, cut short ("...") if longer: for the message only
    uint64_t hash;   // hashBytes of the whole text: what is compared
  };
  std::array<Field, kFields> fields{};
  uint32_t count = 0;  // fields in use, in reportedBefore's order (core/checkpoint.h)
};
static_assert(std::is_trivially_copyable_v<RecordDigest>, "sent as bytes between the ranks");

// The digest of `record`, a JSON object; its nested objects become fields of their own
// ("ppm.direct"). Throws std::logic_error for a record the digest cannot hold (a programming error).
RecordDigest digestRecord(const nlohmann::json& record);

// The first field (in reportedBefore's order) on which rank `rank`'s digest differs from rank 0's (also one that only
// one of them has), described for a message: "seed (rank 0: 1, rank 1: 2)"; empty if none.
std::string firstDifference(const RecordDigest& root, const RecordDigest& other, int rank);

// Thrown on every rank when the ranks disagree. Every rank knows, so the job can end without
// aborting it (MPI_Abort would signal the ranks, each signal handler adding a line): rank 0's error
// is the one line to print ("--mpi: rank R disagrees with rank 0 on FIELD (...)"), the others'
// only end their rank (cli/main.cpp).
class RanksDisagree : public UsageError {
 public:
  RanksDisagree(const std::string& reason, bool print) : UsageError("--mpi", "", reason), print_(print) {}
  bool print() const { return print_; }

 private:
  bool print_;
};

// Every rank, collectively, before any other exchange of the group: rank 0 gathers the digest of
// each rank's record and compares; then every rank learns the lowest rank that differs, if any,
// and throws RanksDisagree.
void requireSameRecord(RenderGroup& group, const nlohmann::json& record);

}  // namespace kasha
