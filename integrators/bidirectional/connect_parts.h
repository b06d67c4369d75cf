#pragma once
// The parts BDPT's strategies share (connect.cpp, merge.cpp): densities next to a connection, the
// light end, the wavelength factors of the weights, the full recomputation for the test oracle,
// the per-lane weights and their records, and visibility.
#include <utility>
#include <vector>

#include "integrators/bidirectional/connect.h"
#include "integrators/bidirectional/subpath_mis.h"

namespace kasha::bidir {

using Kind = PathVertex::Kind;

// The unit direction from `from` towards `to` (at infinity: against the direction light travels).
Vec3 towards(const PathVertex& from, const PathVertex& to);

// Area density at `target` (per sr at infinity) of a solid-angle density at `at`; vertices no
// other strategy can sample (the pinhole, delta lights) get 0.
double toArea(const Scene& scene, float pdfSA, const PathVertex& at, const PathVertex& target);

// The density of `target` sampled at `at` by the subpath of the query's mode (Radiance: the camera
// side's, Importance: the light side's): the spectral event (the query's lobe, the sampled side's
// wavelength given the known one), the direction from wKnown (towards at's neighbour on that
// subpath) to wTarget (towards target), both in at's shading frame (the caller's, which it has for
// its own f), and the free flight over `segment` (the optical depths between at and target at the
// sampled side's wavelength; path_media.h).
double densityToward(const Scene& scene, const ScatterQuery& query, const PathVertex& at, const Vec3& wKnown,
                     const Vec3& wTarget, const PathVertex& target, const SegmentDepth& segment);

// The light end x_0 seen from its neighbour x_1: its positional densities.
struct LightEnd {
  double pdf0 = 0.0;    // pL_0: x_0's position (per sr at infinity), also next-event estimation's
  double pdf1 = 0.0;    // pL_1: the light side's density of x_1 (0 if x_1 is the camera)
  bool finite = false;  // x_0 is at a finite position
};

// `segment`: the optical depths between x_0 and x_1 at the wavelength lambda light leaves x_0 with.
LightEnd lightEnd(const Context& c, int light, const PathVertex& x0, const PathVertex& x1, const SegmentDepth& segment,
                  float lambda);

// The light end of a light subpath whose first s vertices a strategy uses, from what the subpath
// stored (x_1 is the camera when s = 1).
LightEnd storedLightEnd(const std::vector<PathVertex>& L, int s);

// The wavelength factors of the weights (mis_sums.h, docs/bdpt-mis.md §10) for a path whose light
// end is `light` at wavelength lambda0 and whose last wavelength the sensor draws with sensorPdf.
// lane: the camera sample's lane whose wavelength lambda0 is (the path has one group), or −1.
// The camera family's light choice is the true one, the lanes' mixture, where it is the same for
// every strategy that can make the path (one group, the shared family alone); with the own family
// as well, next-event estimation's choice is taken as p(light | λ_0), a function of the path alone,
// so that the weights stay a partition of unity for each lane (the estimates divide by the true
// one), and the shared light subpath's is its true one, the merged start's Q(l).
// lanesKept: every interior vertex of the path keeps the lanes (MisFactors::laneGain). ownStart: the
// own family's ℓ where the caller knows it (an own subpath's L[0].choicePdf), else 0.
MisFactors factors(const Context& c, int light, float lambda0, int lane, double sensorPdf, bool oneGroup,
                   bool lanesKept, float ownStart = 0.0f);

// The full recomputation (test oracle, docs/bdpt-mis.md §5): the stored densities of L[0..s−1],
// C[0..t−1] laid out as x_0 … x_k, with the light end's (and the stored beam ratios: a caller whose
// camera side reaches L[s − 1] otherwise than from L[s] sets that one's). The path ends a connection or a merge at
// L[s − 1], and a connection at C[t − 1] if `connection` (a merge goes on through C[t − 1]'s own
// event): PathVertex::joinable.
FullPath layout(const Context& c, const std::vector<PathVertex>* L, int s, const std::vector<PathVertex>& C, int t,
                const LightEnd& end, const MisFactors& f, bool connection);

// Camera-side spectral density of x_1's event (needed by next-event estimation's density).
double specCamera(const PathVertex& x1, SpectralLobe lobe, float lambda0, float lambda1);

// Light-side spectral density of x_{k−1}'s event, which the t = 1 strategy samples: x_{k−1} is
// the camera subpath's first hit C[1], with its own sampled event unless it is a connection
// vertex (then `lobe`/`lambdaIn` give the connection's).
double specLightLast(const PathVertex& c1, SpectralLobe lobe, float lambdaIn);

// A strategy's weight from the recursive sums: its own c² over the path's whole sum
// (docs/bdpt-mis.md eq. 11), shown to c.observer with `layout(f)`, the path laid out for the full
// recomputation (FullPathLayout; built only if the observer asks, as the test oracle does).
template <class Layout>
float weigh(const Context& c, int s, int t, Variant v, const MisSums& own, const MisSums& total, const MisFactors& f,
            Layout&& layout) {
  const double sum = combine(total, f);
  const float w = sum > 0.0 ? float(combine(own, f) / sum) : 0.0f;
  if (c.observer) c.observer->onWeight({c, s, t, v, w, total, f, sum, FullPathLayout(layout)});
  return w;
}

// The lane an own-family join at camera vertex b serves, and its factor: with several lanes at b,
// one chosen uniformly with b's own number, its estimate times n (an unbiased one-sample estimate
// of the sum over the lanes).
std::pair<int, float> ownJoinLane(const Context& c, const PathVertex& b);

// Each lane's weight in [k0, k1) where active(k), from weighLane(k): per lane where the own family
// runs (its factors differ between lanes), once for all otherwise (docs/bdpt-mis.md §10).
template <class Active, class WeighLane>
void laneWeights(const Context& c, int k0, int k1, float* w, Active&& active, WeighLane&& weighLane) {
  int first = -1;
  for (int k = k0; k < k1; ++k) {
    w[k] = 0.0f;
    if (!active(k)) continue;
    if (first >= 0 && !c.families.independent) {
      w[k] = w[first];
      if (c.observer) c.observer->onLaneCopied(k, first);
      continue;
    }
    w[k] = weighLane(k);
    if (c.observer) c.observer->onLaneKept(k);
    first = k;
  }
}

// A join between ends that several lanes reach, whose segment runs through a medium: its densities
// depend on λ, so it serves lane 0 alone, its estimate (value[0]) times n, and the other lanes get 0
// (docs/media.md §5). Unbiased as where a subpath's lanes end (docs/bdpt-mis.md §10): everything
// sampled before the join is symmetric in the lanes, so lane 0 is a uniform choice among them.
void laneZeroThroughMedia(const Context& c, float* value);

// XYZ per unit radiance of lane k at the camera: W(λ_k)/(n·p(λ_k)).
Vec3 laneScale(const Context& c, int k);
// The factor of a connection or merge between two shared-family ends that carry one lane each
// (laneA, laneB; -1 where every lane reaches): both ended their lanes in the same hero lane, one
// choice of probability 1/n whose factor n each end's throughput already holds, so 1/n; else 1.
float keptLaneScale(const Context& c, int laneA, int laneB);

// Reports lane k's share of a strategy at the camera sample's pixel (strategies with t ≥ 2) to
// c.observer, if any.
void record(const Context& c, int s, int t, Variant v, int k, float value, float weight);
// The same for a contribution whose XYZ (unweighted) the caller has, in lane k's slot; c.observer
// must be set.
void recordXyz(const Context& c, int s, int t, Variant v, int k, const Vec3& xyz, float weight);

// The radiance an emitter vertex e sends towards `next` at wavelength lambda.
float emitted(const Context& c, const PathVertex& e, const PathVertex& next, float lambda);

// Whether no surface blocks the segment between a and b; in a scene with media, also its optical
// depths at lambda (through the media it crosses, from the one a leaves into).
bool visible(const Context& c, const PathVertex& a, const PathVertex& b, float lambda = 0.0f,
             SegmentDepth* depth = nullptr);

// The transmittance of a segment of optical depths d (1 where it crosses no medium, without a call
// to exp: connections in scenes without media multiply by it too).
inline float transmittance(const SegmentDepth& d) { return d.analog > 0.0f ? std::exp(-d.analog) : 1.0f; }

// The camera side's sum at a connection through C[t−1] (docs/bdpt-mis.md eq. 10): C[t−1] with the
// light side's density pLast and `mLast` the M of the strategy with t − 1 camera vertices; C[t−2]
// with the light side's density pBefore.
MisSums cameraSum(const Context& c, const std::vector<PathVertex>& C, int t, double pLast, const MisSums& mLast,
                  double pBefore);

// The light side's sum at a connection through L[s−1] (s ≥ 2; eq. 10): L[s−1] with the camera
// side's density pLast and `mLast` the M of the strategy with s − 1 light vertices; L[s−2] with
// the camera side's density pBefore.
MisSums lightSum(const Context& c, const std::vector<PathVertex>& L, int s, double pLast, const MisSums& mLast,
                 double pBefore);

// The light side's sum of a strategy whose light subpath ends at x_0 (s = 1): the camera side's
// density pCam0 of it over the light side's, pLight0.
MisSums lightEndSum(double pCam0, double pLight0);

}  // namespace kasha::bidir
