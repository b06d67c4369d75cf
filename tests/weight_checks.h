#pragma once
// The test oracle of BDPT's recursive weights (docs/bdpt-mis.md §9): every weight the estimator
// computes, recomputed over the whole path (integrators/bidirectional/mis.h, §5), and their tally: each pair
// must agree (relative 1e-5), and the comparison must not be vacuous.
#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <string>
#include <vector>

#include "integrators/bidirectional/mis_observer.h"

namespace kasha::test {

// One weight both ways.
struct WeightCheck {
  int s, t;
  uint8_t variant;  // bidir::Variant
  float recursive, full;
};

// Watches the estimator (Context::observer) and recomputes each weight it computes from the path
// laid out (FullPathLayout).
class WeightOracle final : public bidir::MisObserver {
 public:
  std::vector<WeightCheck> checks;
  void onWeight(const bidir::WeightEvent& e) override {
    const float full = bidir::misWeight(e.layout(e.factors), e.s, e.variant);
    checks.push_back({e.s, e.t, uint8_t(e.variant), e.weight, full});
  }
};

struct WeightTally {
  int compared = 0;
  std::map<std::pair<int, int>, int> interior;  // (variant, s + t) → weights strictly inside (0, 1)

  // Checks every pair of `checks` (one camera sample's); false after the first that disagrees.
  bool add(const std::vector<WeightCheck>& checks, uint32_t sample) {
    for (const WeightCheck& k : checks) {
      ++compared;
      EXPECT_NEAR(k.recursive, k.full, 1e-5f * std::max(k.recursive, k.full) + 1e-9f)
          << "s = " << k.s << ", t = " << k.t << ", variant " << int(k.variant) << ", sample " << sample;
      if (!(std::abs(k.recursive - k.full) <= 1e-5f * std::max(k.recursive, k.full) + 1e-9f)) return false;
      if (k.full > 1e-3f && k.full < 0.999f) ++interior[{k.variant, k.s + k.t}];
    }
    return true;
  }

  // The comparison is not vacuous: more than `minCompared` weights, of several (variant, length)
  // classes, with more than 200 strictly between 0 and 1 (where a wrong term would show).
  void expectPower(int minCompared, const std::string& what) const {
    EXPECT_GT(compared, minCompared) << what;
    int inside = 0;
    for (const auto& [key, n] : interior) inside += n;
    EXPECT_GT(inside, 200) << what;
    EXPECT_GE(interior.size(), 2u) << what << ": (variant, length) classes with weights inside (0, 1)";
  }
};

}  // namespace kasha::test
