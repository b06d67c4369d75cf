#pragma once
// Light subpaths traced in parallel chunks whose records come back in path order (the photon pass,
// vertex merging's light vertices), so that the result does not depend on the number of threads,
// with a memory limit checked as the records accumulate.
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <string>
#include <vector>

#include "core/memory_budget.h"
#include "integrators/integrator.h"

namespace kasha {

// What the records of traceInChunks are, for its memory message: "the photon map of one pass",
// "photons", "render/ppm/photons_per_pass".
struct ChunkedRecords {
  const char *store, *records, *pathsSetting;
};

// Calls trace(j, records, counter) for every path j < paths, 1024 paths to a chunk, each chunk with
// its own buffer and ray counter; returns the records in path order and adds the rays to `counter`.
// Throws MemoryLimitError ("<store> (at least n <records> …) needs …", n the records kept so far) as
// soon as the records kept exceed memoryLimit / bytesPerRecord.
template <class Record, class Trace>
std::vector<Record> traceInChunks(size_t paths, uint64_t memoryLimit, size_t bytesPerRecord, const ChunkedRecords& what,
                                  RayCounter& counter, Trace&& trace) {
  constexpr size_t kPathsPerChunk = 1024;
  const size_t chunks = (paths + kPathsPerChunk - 1) / kPathsPerChunk;
  std::vector<std::vector<Record>> parts(chunks);
  std::vector<RayCounter> counters(chunks);
  const size_t maxKept = size_t(memoryLimit / bytesPerRecord);
  std::atomic<size_t> kept{0};
  std::atomic<bool> overflow{false};
  tbb::parallel_for(tbb::blocked_range<size_t>(0, chunks, 1), [&](const tbb::blocked_range<size_t>& range) {
    for (size_t c = range.begin(); c < range.end() && !overflow.load(std::memory_order_relaxed); ++c) {
      const size_t end = std::min(paths, (c + 1) * kPathsPerChunk);
      for (size_t j = c * kPathsPerChunk; j < end; ++j) trace(j, parts[c], counters[c]);
      if (kept.fetch_add(parts[c].size()) + parts[c].size() > maxKept) overflow = true;
    }
  });
  for (const RayCounter& c : counters) counter.closest += c.closest, counter.shadow += c.shadow;
  const size_t total = kept.load();
  if (overflow)
    requireMemory(saturatingMul(total, bytesPerRecord),
                  std::string(what.store) + " (at least " + std::to_string(total) + " " + what.records + " × " +
                      std::to_string(bytesPerRecord) + " bytes from " + std::to_string(paths) + " light subpaths; lower " +
                      what.pathsSetting + ")",
                  memoryLimit);
  // The records in path order: each chunk's at its offset, copied in parallel, each chunk freed once copied.
  std::vector<size_t> offset(chunks + 1, 0);
  for (size_t c = 0; c < chunks; ++c) offset[c + 1] = offset[c] + parts[c].size();
  std::vector<Record> out(total);
  tbb::parallel_for(size_t(0), chunks, [&](size_t c) {
    std::copy(parts[c].begin(), parts[c].end(), out.begin() + long(offset[c]));
    std::vector<Record>().swap(parts[c]);
  });
  return out;
}

}  // namespace kasha
