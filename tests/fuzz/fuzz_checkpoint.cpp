// libFuzzer target: the checkpoint reader (core/checkpoint.h) on arbitrary bytes. A checkpoint is
// refused with an InputError naming the file (truncated, corrupted, forged, foreign, another byte
// order), or it is read whole: a film of the size its header states, every sum finite. Buffers are
// allocated only up to the file's size, so no input may allocate more than it holds
// (-rss_limit_mb). Anything else is a finding.
//
// The reader verifies the checksum before it parses the header, so mutated bytes would almost never
// get past it: each input is also read with its last 8 bytes replaced by the checksum of the bytes
// before them (hashBytes, as a forger would), which takes the header to the parser.
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

#include "core/checkpoint.h"
#include "core/error.h"
#include "tests/fuzz/fuzz_support.h"

namespace {

// A broken promise is a finding.
void require(bool ok, const char* what) { kasha::fuzz::require(ok, "fuzz_checkpoint", what); }

void readOne(const std::string& bytes) {
  using namespace kasha;
  const std::string path = fuzz::writeInput("fuzz.ckpt", reinterpret_cast<const uint8_t*>(bytes.data()), bytes.size());
  try {
    const CheckpointData d = readCheckpoint(path);
    const size_t pixels = size_t(d.width) * size_t(d.height);
    require(d.sums.size() == pixels && d.splats.size() == pixels, "a film of the stated size");
    for (const auto* b : {&d.sums, &d.splats})
      for (const auto& v : *b) require(std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z), "finite sums");
  } catch (const InputError& e) {
    require(std::string(e.what()).rfind(path, 0) == 0, "the message names the file");
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  std::string bytes(reinterpret_cast<const char*>(data), size);
  readOne(bytes);
  if (size >= 8) {
    const uint64_t sum = kasha::hashBytes(bytes.data(), size - 8);
    std::memcpy(bytes.data() + size - 8, &sum, sizeof sum);
    readOne(bytes);
  }
  return 0;
}
