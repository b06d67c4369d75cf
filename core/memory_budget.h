#pragma once
// Memory limits: a large buffer (film, mesh, photon map) is checked against a configurable limit
// before it is allocated, so that exceeding it is a clear error and not an out-of-memory kill.
// Each buffer is checked on its own against the whole limit (`kasha render --memory-limit`).
#include <cstdint>
#include <stdexcept>
#include <string>

namespace kasha {

// The default limit: 8 GiB.
constexpr uint64_t kDefaultMemoryLimit = uint64_t(8) << 30;

class MemoryLimitError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Throws MemoryLimitError "<what> needs <bytes>, more than the memory limit of <limit> (raise it
// with --memory-limit)" if bytes > limit. `what` names the buffer, e.g. "the film (1920×1080 pixels)".
void requireMemory(uint64_t bytes, const std::string& what, uint64_t limit);

// a·b, saturating at UINT64_MAX instead of wrapping (sizes computed from user input).
inline uint64_t saturatingMul(uint64_t a, uint64_t b) {
  return (a != 0 && b > UINT64_MAX / a) ? UINT64_MAX : a * b;
}

// "8G", "512M", "1.5G", "65536", "64KiB": bytes with an optional binary suffix K, M, G, T (×1024ⁿ;
// "B" and "iB" may follow, case does not matter). Throws std::invalid_argument with the reason.
uint64_t parseByteSize(const std::string& text);

// "12.0 GiB", "512 KiB", "100 bytes".
std::string formatBytes(uint64_t bytes);

}  // namespace kasha
