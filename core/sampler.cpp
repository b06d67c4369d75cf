#include "core/sampler.h"

#include <array>

namespace kasha {
namespace sobol {
namespace {

}  // namespace

uint32_t reverseBits(uint32_t v) {
  v = ((v >> 1) & 0x55555555u) | ((v & 0x55555555u) << 1);
  v = ((v >> 2) & 0x33333333u) | ((v & 0x33333333u) << 2);
  v = ((v >> 4) & 0x0f0f0f0fu) | ((v & 0x0f0f0f0fu) << 4);
  v = ((v >> 8) & 0x00ff00ffu) | ((v & 0x00ff00ffu) << 8);
  return (v >> 16) | (v << 16);
}

namespace {

// Direction numbers of Sobol's second dimension: polynomial x + 1, m_1 = 1, so
// v_k = v_{k−1} XOR (v_{k−1} >> 1) as 32-bit fractions (v_1 = 1/2).
constexpr std::array<uint32_t, 32> directions1() {
  std::array<uint32_t, 32> v{};
  v[0] = 0x80000000u;
  for (size_t k = 1; k < v.size(); ++k) v[k] = v[k - 1] ^ (v[k - 1] >> 1);
  return v;
}
constexpr std::array<uint32_t, 32> kDirections1 = directions1();

// The same, bit-reversed: XOR-ing them gives reverseBits(dimension1(index)) directly.
constexpr std::array<uint32_t, 32> reversedDirections1() {
  std::array<uint32_t, 32> r{};
  for (size_t k = 0; k < r.size(); ++k)
    for (int b = 0; b < 32; ++b)
      if (kDirections1[k] & (1u << b)) r[k] |= 1u << (31 - b);
  return r;
}
constexpr std::array<uint32_t, 32> kReversedDirections1 = reversedDirections1();

// Byte tables of the same: entry [b][x] is the XOR of the reversed directions of the set bits of
// byte x at byte position b, so that a 32-bit index takes four lookups instead of a loop over its
// bits (whose branches a random index mispredicts).
constexpr std::array<std::array<uint32_t, 256>, 4> reversedDirectionBytes() {
  std::array<std::array<uint32_t, 256>, 4> t{};
  for (size_t b = 0; b < 4; ++b)
    for (size_t x = 0; x < 256; ++x)
      for (size_t k = 0; k < 8; ++k)
        if (x & (size_t(1) << k)) t[b][x] ^= kReversedDirections1[8 * b + k];
  return t;
}
constexpr std::array<std::array<uint32_t, 256>, 4> kReversedDirectionBytes = reversedDirectionBytes();

// Burley 2020 §3 (Laine & Karras 2011's permutation with Burley's constants): a bijection of
// 32-bit integers in which bit i of the result depends only on bits 0..i of the input.
uint32_t laineKarras(uint32_t x, uint32_t seed) {
  x += seed;
  x ^= x * 0x6c50b47cu;
  x ^= x * 0xb82f1e52u;
  x ^= x * 0xc7afe638u;
  x ^= x * 0x8d22f6e6u;
  return x;
}

}  // namespace

uint32_t dimension0(uint32_t index) { return reverseBits(index); }

uint32_t dimension1(uint32_t index) {
  uint32_t v = 0;
  for (int k = 0; index != 0; ++k, index >>= 1)
    if (index & 1u) v ^= kDirections1[size_t(k)];
  return v;
}

uint32_t reversedDimension1(uint32_t index) {
  return kReversedDirectionBytes[0][index & 0xffu] ^ kReversedDirectionBytes[1][(index >> 8) & 0xffu] ^
         kReversedDirectionBytes[2][(index >> 16) & 0xffu] ^ kReversedDirectionBytes[3][index >> 24];
}

uint32_t laineKarrasPermutation(uint32_t x, uint32_t seed) { return laineKarras(x, seed); }

// Bit-reversed, the permutation lets each bit depend on the more significant ones only: a
// nested uniform scramble of the fraction (Burley 2020 eq. 3).
uint32_t owenScramble(uint32_t v, uint32_t seed) { return reverseBits(laineKarras(reverseBits(v), seed)); }

}  // namespace sobol

namespace {
float toUnit(uint32_t v) { return float(v >> 8) * 0x1p-24f; }
}  // namespace

const char* toString(SamplerKind k) { return k == SamplerKind::Sobol ? "sobol" : "independent"; }

std::optional<SamplerKind> parseSamplerKind(const std::string& name) {
  if (name == "sobol") return SamplerKind::Sobol;
  if (name == "independent") return SamplerKind::Independent;
  return std::nullopt;
}

namespace {
// mixBits((dimension << 2) | salt) of the first kTabulatedDimensions dimensions.
constexpr uint32_t kTabulatedDimensions = 1024;
const std::array<uint64_t, kTabulatedDimensions * 4>& dimensionHashes() {
  static const std::array<uint64_t, kTabulatedDimensions * 4> table = [] {
    std::array<uint64_t, kTabulatedDimensions * 4> t{};
    for (uint32_t i = 0; i < t.size(); ++i) t[i] = mixBits(uint64_t(i));
    return t;
  }();
  return table;
}
}  // namespace

Sampler::Sampler(SamplerKind kind, uint64_t seed, uint64_t stream, uint32_t sample)
    : kind_(kind),
      rng_(mixBits(seed ^ mixBits(stream)), uint64_t(sample)),
      key_(mixBits(seed ^ mixBits(stream))),
      reversedSample_(sobol::reverseBits(sample)) {}

uint32_t Sampler::scrambleKey(uint32_t dim, uint32_t salt) const {
  const uint64_t slot = (uint64_t(dim) << 2) | salt;
  return uint32_t(mixBits(key_ ^ (slot < dimensionHashes().size() ? dimensionHashes()[slot] : mixBits(slot))));
}

uint32_t Sampler::shuffledIndex(uint32_t key) const {
  // owenScramble(sample, key) with the sample's reversal computed once.
  return sobol::reverseBits(sobol::laineKarrasPermutation(reversedSample_, key));
}

float Sampler::uniform() {
  if (kind_ == SamplerKind::Independent) return rng_.uniform();
  const uint32_t d = dim_++;
  // Burley 2020 §4: each padded dimension shuffles the sample order by its own scramble.
  const uint32_t index = shuffledIndex(scrambleKey(d, 0));
  // owenScramble(dimension0(index), ·) = reverseBits(LK(index, ·)): dimension0 is a reversal.
  return toUnit(sobol::reverseBits(sobol::laineKarrasPermutation(index, scrambleKey(d, 1))));
}

Vec2 Sampler::uniform2() {
  if (kind_ == SamplerKind::Independent) {
    const float x = rng_.uniform();
    return Vec2(x, rng_.uniform());
  }
  const uint32_t d = dim_;
  dim_ += 2;
  const uint32_t index = shuffledIndex(scrambleKey(d, 0));
  return Vec2(toUnit(sobol::reverseBits(sobol::laineKarrasPermutation(index, scrambleKey(d, 1)))),
              toUnit(sobol::reverseBits(sobol::laineKarrasPermutation(sobol::reversedDimension1(index), scrambleKey(d, 2)))));
}

}  // namespace kasha
