#pragma once
// The random numbers of one pixel sample (or one light path of a pass), by dimension.
//
// A sample is identified by (seed, stream, sample index): the stream is the pixel (or the light
// path's index within its pass) and the index the sample number, so sample s of pixel p depends
// only on (seed, p, s) and images do not depend on threads, tiles or checkpoints.
//
// Kinds
// - Sobol (default): the first two dimensions of Sobol's sequence, Owen-scrambled by the hashed
//   nested uniform scramble of Burley 2020 ("Practical Hash-based Owen Scrambling", JCGT 9(4)),
//   with "padding": every dimension (or pair, for uniform2) has its own scramble and its own
//   Owen-scrambled shuffle of the sample index (Burley 2020 §4), keyed by (seed, stream, dimension).
//   The first 2^k samples of a stream then form a (0, k, 2)-net in each pair and a stratified
//   set in each single dimension, and every point is uniform in [0, 1)^d (an unbiased estimator).
// - Independent: PCG32 with its own stream per (seed, stream, sample) (core/rng.h).
//
// Dimensions are consumed in call order; an integrator that wants a fixed layout per path vertex
// calls setDimension() at the vertex (docs/sampler.md gives kasha's layout).
#include <cstdint>
#include <optional>
#include <string>

#include "core/math.h"
#include "core/rng.h"

namespace kasha {

enum class SamplerKind : uint8_t { Sobol, Independent };
const char* toString(SamplerKind k);
// "sobol" or "independent"; nullopt otherwise.
std::optional<SamplerKind> parseSamplerKind(const std::string& name);

class Sampler {
 public:
  Sampler(SamplerKind kind, uint64_t seed, uint64_t stream, uint32_t sample);

  // The next dimension, uniform in [0, 1) (never 1).
  float uniform();
  // The next two dimensions, stratified jointly.
  Vec2 uniform2();
  // The next three dimensions: one, then a jointly stratified pair (a material's spectral stage
  // and its direction, Material::sample).
  Vec3 uniform3() {
    const float x = uniform();
    return Vec3(x, uniform2());
  }
  // Continue at dimension d (a fixed slot of a layout).
  void setDimension(uint32_t d) { dim_ = d; }
  // The layout of the path tracers (docs/sampler.md): a path that starts at dimension `start`
  // draws the events of its vertex `depth` from a block of kVertexDimensions dimensions of its own,
  // so that a vertex's numbers do not shift with the events of the vertices before it.
  static constexpr uint32_t kVertexDimensions = 8;
  void startVertex(uint32_t start, int depth) { dim_ = start + uint32_t(depth) * kVertexDimensions; }
  uint32_t dimension() const { return dim_; }

 private:
  // Scrambling seed of a dimension: salt 0 shuffles the sample index (Burley 2020 §4), 1 and 2
  // scramble the first and second coordinate.
  uint32_t scrambleKey(uint32_t dim, uint32_t salt) const;
  // The sample's index in a dimension's own shuffled order.
  uint32_t shuffledIndex(uint32_t key) const;

  SamplerKind kind_;
  Rng rng_;
  uint64_t key_;
  uint32_t reversedSample_;  // sobol::reverseBits of the sample's index
  uint32_t dim_ = 0;
};

// Building blocks of the Sobol kind, exposed for the tests.
namespace sobol {
// Sobol's first dimension (the van der Corput sequence in base 2) and second dimension (the
// generator matrix of the primitive polynomial x + 1), as 32-bit fractions.
uint32_t dimension0(uint32_t index);
uint32_t dimension1(uint32_t index);
// reverseBits(dimension1(index)), without the reversal.
uint32_t reversedDimension1(uint32_t index);
uint32_t reverseBits(uint32_t v);
// Burley 2020's Laine–Karras permutation: bit i of the result depends on bits 0..i of x only.
uint32_t laineKarrasPermutation(uint32_t x, uint32_t seed);
// Burley 2020 §3: a nested uniform (Owen) scramble of the bits of a 32-bit fraction, from the
// most significant bit down, keyed by seed.
uint32_t owenScramble(uint32_t v, uint32_t seed);
}  // namespace sobol

}  // namespace kasha
