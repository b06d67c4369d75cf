#pragma once
// What watches the bidirectional estimator without changing it: the recursive-weight test oracle
// (tests/weight_checks.h, docs/bdpt-mis.md §9), the per-strategy images (strategy_images.h, §7) and
// the pilots (pilot_observer.h, §13–14) see each weight, each lane's share of it and each
// contribution through this one interface, so that the strategies compute weights and
// contributions and nothing else. A normal render has none: Context::observer is null, and each
// call site costs one test of it.
#include "integrators/bidirectional/mis.h"
#include "integrators/bidirectional/mis_sums.h"
#include "integrators/integrator.h"

namespace kasha::bidir {

struct Context;

// A weight's full path laid out for mis.h's recomputation (§5), built only when called: it refers
// to the strategy's callable, which outlives it (weigh()'s call).
class FullPathLayout {
 public:
  template <class Layout>
  explicit FullPathLayout(const Layout& layout)
      : layout_(&layout),
        call_([](const void* l, const MisFactors& f) { return (*static_cast<const Layout*>(l))(f); }) {}
  // The path with the factors f.
  FullPath operator()(const MisFactors& f) const { return call_(layout_, f); }

 private:
  const void* layout_;
  FullPath (*call_)(const void*, const MisFactors&);
};

// One weight as weigh() computed it (docs/bdpt-mis.md eq. 11): strategy (s, t, variant) of the
// camera sample `c`, its value, the path's sums and factors, and `sum`, their combination (the
// power heuristic's denominator).
struct WeightEvent {
  const Context& c;
  int s, t;
  Variant variant;
  float weight;
  const MisSums& total;
  const MisFactors& factors;
  double sum;
  FullPathLayout layout;
};

class MisObserver {
 public:
  virtual ~MisObserver() = default;
  // Every weight computed.
  virtual void onWeight(const WeightEvent&) {}
  // Lane k's weight is the one computed last, or lane `from`'s (laneWeights(), docs/bdpt-mis.md §10).
  virtual void onLaneKept(int /*k*/) {}
  virtual void onLaneCopied(int /*k*/, int /*from*/) {}
  // Lane k adds `weighted` (XYZ) at `pixel`: the camera sample's for t ≥ 2, the splat's for t = 1.
  virtual void onContribution(int /*k*/, Vec2 /*pixel*/, const Vec3& /*weighted*/) {}
  // A strategy's contribution, with its weight and without.
  virtual void onStrategy(const StrategySample&) {}
};

}  // namespace kasha::bidir
