#pragma once
// PCG32 (O'Neill 2014, pcg-random.org, "pcg32_random_r"): a small, fast, reproducible generator.
// Each pixel sample gets its own stream, so images do not depend on the thread count.
#include <cstdint>

namespace kasha {

class Rng {
 public:
  explicit Rng(uint64_t seed = 0x853c49e6748fea9bULL, uint64_t stream = 0xda3e39cb94b95bdbULL) {
    state_ = 0;
    inc_ = (stream << 1u) | 1u;
    nextU32();
    state_ += seed;
    nextU32();
  }
  uint32_t nextU32() {
    const uint64_t old = state_;
    state_ = old * 6364136223846793005ULL + inc_;
    const uint32_t xorshifted = static_cast<uint32_t>(((old >> 18u) ^ old) >> 27u);
    const uint32_t rot = static_cast<uint32_t>(old >> 59u);
    return (xorshifted >> rot) | (xorshifted << ((-rot) & 31));
  }
  // Uniform in [0, 1): 24 random bits, so the result is never rounded up to 1.
  float uniform() { return static_cast<float>(nextU32() >> 8) * 0x1p-24f; }

 private:
  uint64_t state_, inc_;
};

// SplitMix64 finaliser: turns (seed, pixel, sample) into well-mixed stream parameters.
inline uint64_t mixBits(uint64_t v) {
  v ^= v >> 30;
  v *= 0xbf58476d1ce4e5b9ULL;
  v ^= v >> 27;
  v *= 0x94d049bb133111ebULL;
  v ^= v >> 31;
  return v;
}

}  // namespace kasha
