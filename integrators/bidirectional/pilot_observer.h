#pragma once
// What the pilots learn from the estimator's own paths (docs/bdpt-mis.md §13, §14), watching it
// through MisObserver: for each contribution, how much better or worse an alternative estimator
// would sample its path, and the merge weights computed (vcm's cost model).
#include <cmath>
#include <cstdint>
#include <vector>

#include "integrators/bidirectional/mis_observer.h"
#include "integrators/wavelength_lanes.h"

namespace kasha::bidir {

// The estimators a pilot weighs against the one it runs (docs/bdpt-mis.md §13, §14): each family
// alone, as bdpt-shared and bdpt-independent run it (the unified bdpt's pilot), camera paths alone,
// path tracing with next-event estimation, and the connections alone, vc's estimator (vcm's).
enum class Alone { Shared = 0, Own = 1, Camera = 2, Connections = 3 };
constexpr int kAlternatives = 4;

// What the pilot learns from one camera sample of both families about each alternative, from the
// weights' sums: for each contribution C (film XYZ), ρ = p_both/p_alone, the two estimators'
// densities of the path (√ of the ratio of their power-heuristic sums), and the second moment
// running the family alone would add, C²·(ρ − 1) (Grittmann et al. 2022; negative where the family
// alone samples the path better), or that p_alone = 0.
struct PilotMoments {
  struct Alternative {
    double ratio[kMaxLanes] = {};  // ρ of the strategy weighed last, per lane (laneWeights)
    double pending = 1.0;          // ρ of the strategy weigh() saw last
    int unsampled = 0;             // contributions on paths the family alone cannot sample
    std::vector<Splat> excess;     // per contribution: its pixel and C²·(ρ − 1) per channel
  };
  Alternative alone[kAlternatives];

  void clear() {
    for (Alternative& a : alone) a.unsampled = 0, a.excess.clear();
  }
  // Lane k takes the ratios weigh() saw last.
  void keep(int k) {
    for (Alternative& a : alone) a.ratio[k] = a.pending;
  }
  // Lane k takes lane `from`'s ratios.
  void copy(int k, int from) {
    for (Alternative& a : alone) a.ratio[k] = a.ratio[from];
  }
  // Adds lane k's contribution xyz at `pixel`.
  void add(int k, Vec2 pixel, const Vec3& xyz) {
    if (!(xyz.x > 0.0f || xyz.y > 0.0f || xyz.z > 0.0f)) return;
    for (Alternative& a : alone) {
      if (!std::isfinite(a.ratio[k])) ++a.unsampled;
      else if (a.ratio[k] != 1.0) a.excess.push_back({pixel, xyz * xyz * float(a.ratio[k] - 1.0)});
    }
  }
};

// ρ = p_both/p_alone for a path whose sums with the unified estimator's factors f are `total`
// (their combination `sum`): p_alone the density of one family alone as bdpt-shared or
// bdpt-independent runs it (the other family's terms gone; the shared light subpath choosing the
// light as next-event estimation does, the own one its light and wavelength as bdpt-independent's,
// ℓ = ownAloneChoice), of camera paths alone (the camera subpath reaching the light and next-event
// estimation: both families' terms gone), or of the connections alone, vc's (the merges' terms and
// the mollified joins' gone: vc has no wavelength kernel); the
// square root of the ratio of the power-heuristic sums; infinite where p_alone = 0.
double densityOverAlone(Alone alone, const MisSums& total, const MisFactors& f, double sum, double ownAloneChoice);

// Counts the merge weights computed (vcm's pilot: their cost, docs/bdpt-mis.md §14).
class MergeWeightCount : public MisObserver {
 public:
  uint64_t count = 0;
  void onWeight(const WeightEvent& e) override {
    if (isMerge(e.variant)) ++count;
  }
};

// The pilots' observer: each weight's ρ of every alternative (PilotMoments::pending), kept per lane,
// and each contribution's excess; and, as MergeWeightCount, the merge weights.
class PilotObserver final : public MergeWeightCount {
 public:
  explicit PilotObserver(PilotMoments& moments) : moments_(moments) {}
  // ρ for the shared family alone is 1 on paths of one group, where it has every strategy (§5);
  // for it and camera paths alone, also where the path carries no light for a reason the weights
  // know, a wavelength the sensor does not see (σ = 0) or one its light does not emit (κ = 0);
  // infinite where an alternative cannot sample the path.
  void onWeight(const WeightEvent& e) override;
  void onLaneKept(int k) override { moments_.keep(k); }
  void onLaneCopied(int k, int from) override { moments_.copy(k, from); }
  void onContribution(int k, Vec2 pixel, const Vec3& weighted) override { moments_.add(k, pixel, weighted); }

 private:
  PilotMoments& moments_;
};

}  // namespace kasha::bidir
