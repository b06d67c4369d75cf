// Free flights and transmittance through media (integrators/medium_transport.h, docs/media.md §3)
// against the piecewise-exponential closed forms of a ray through two nested spheres of
// index-matched, chromatic media: from x = −3 along +x the ray is in vacuum on [0, 1), in
// "outer" on [1, 2), in "inner" on [2, 4), in "outer" on [4, 5) and in vacuum beyond, so lane k's
// optical depth at distance t is τ_k(t) = Σ σ_t(λ_k)·(length of each medium's part of [0, t]),
// its transmittance T_k(t) = exp(−τ_k(t)) and its collision density σ_t(λ_k, t)·T_k(t).
//   - Lane 0's collision distances follow that density (χ²), escaping with T_0(5).
//   - Per lane k, weight_k·σ_t,k at a collision and weight_k on escape estimate lane k's own
//     collision probability per interval and its transmittance, both on their own (a fixed hero)
//     and with the lanes' spectral MIS (LaneRatios::misWeight, hero chosen among symmetric
//     strata).
//   - segmentTransmittance is exp(−Σσ_t·d), and false when a surface blocks the segment; shadow
//     rays (lightTransmittance) start in the medium on their side of a boundary (VertexMedium).
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <vector>

#include "core/rng.h"
#include "integrators/medium_transport.h"
#include "scene/scene_loader.h"
#include "tests/support.h"

namespace kasha {
namespace {

// σ_t = σ_a + σ_s of the two media, σ_a linear in λ over the range (tabulated below).
double sigmaOuter(double lambda) { return 0.02 + 0.78 * (lambda - 360.0) / 470.0 + 0.03; }
double sigmaInner(double lambda) { return 1.0 - 0.98 * (lambda - 360.0) / 470.0 + 0.03; }

constexpr const char* kScene = R"({
  "camera": {"position": [0, 0, -8], "look_at": [0, 0, 0], "fov": 40, "resolution": [4, 4]},
  "materials": {"white": {"type": "lambertian", "reflectance": 0.5}},
  "media": {
    "outer": {"type": "homogeneous", "sigma_s": 0.03,
              "sigma_a": {"type": "tabulated", "wavelengths": [360, 830], "values": [0.02, 0.8]}},
    "inner": {"type": "homogeneous", "sigma_s": 0.03, "g": 0.5,
              "sigma_a": {"type": "tabulated", "wavelengths": [360, 830], "values": [1.0, 0.02]}}},
  "shapes": [
    {"type": "sphere", "center": [0, 0, 0], "radius": 2, "interior": "outer"},
    {"type": "sphere", "center": [0, 0, 0], "radius": 1, "interior": "inner", "exterior": "outer"},
    {"type": "rectangle", "center": [0, 3, 0], "u": [1, 0, 0], "v": [0, 0, 1], "material": "white"}],
  "lights": [{"type": "point", "position": [0, 50, 0], "intensity": 1}]
})";

// The media along the ray from x = −3 along +x: [start, end) and σ_t.
struct Piece {
  double start, end;
  double (*sigma)(double);
};
const Piece kPieces[] = {{1, 2, sigmaOuter}, {2, 4, sigmaInner}, {4, 5, sigmaOuter}};

double opticalDepth(double lambda, double t) {
  double tau = 0.0;
  for (const Piece& p : kPieces) tau += p.sigma(lambda) * std::clamp(t - p.start, 0.0, p.end - p.start);
  return tau;
}
double transmittance(double lambda, double t) { return std::exp(-opticalDepth(lambda, t)); }
double sigmaAt(double lambda, double t) {
  for (const Piece& p : kPieces)
    if (t >= p.start && t < p.end) return p.sigma(lambda);
  return 0.0;
}

// Symmetric strata of the range, as the lanes are drawn.
constexpr int kLanes = 4;
const std::array<float, kLanes> kLambdas = {418.75f, 536.25f, 653.75f, 771.25f};

class FreeFlightTest : public ::testing::Test {
 protected:
  void SetUp() override {
    SceneLoadOptions options;
    options.notes = nullptr;
    scene = loadSceneFromString(kScene, "media_transport.json", options);
    ASSERT_EQ(scene->media.size(), 2u);
  }
  int mediumNamed(const std::string& name) const {
    for (size_t i = 0; i < scene->media.size(); ++i)
      if (scene->media[i]->name() == name) return int(i);
    return -1;
  }
  FreeFlight fly(const std::array<float, kLanes>& lambda, float u, Vec3 origin = Vec3(-3, 0, 0),
                 Vec3 d = Vec3(1, 0, 0), int medium = -1) {
    return traceFreeFlight(*scene, Ray{origin, d}, medium, lambda, u, TransportMode::Radiance, counter);
  }
  std::unique_ptr<Scene> scene;
  RayCounter counter;
};

TEST_F(FreeFlightTest, HeroCollisionDistancesArePiecewiseExponential) {
  for (const float hero : {kLambdas[0], kLambdas[3]}) {
    SCOPED_TRACE("λ_0 = " + std::to_string(hero));
    const int bins = 40, n = 40000;  // 0.1 wide over [1, 5), then escape
    std::vector<double> observed(bins + 2, 0.0), expected(bins + 2, 0.0);
    Rng rng(uint64_t(hero), 9);
    for (int i = 0; i < n; ++i) {
      const std::array<float, kLanes> lambda = {hero, 500.0f, 600.0f, 700.0f};
      const FreeFlight f = fly(lambda, rng.uniform());
      if (!f.collided) {
        ASSERT_FALSE(f.hit.has_value());
        ASSERT_EQ(f.medium, -1);
        observed[bins] += 1.0;
        continue;
      }
      const double t = f.p.x + 3.0;
      ASSERT_NEAR(f.p.y, 0.0f, 1e-5f);
      const int b = int(std::floor((t - 1.0) / 0.1));
      observed[b >= 0 && b < bins ? size_t(b) : size_t(bins + 1)] += 1.0;  // before 1 or after 5: nothing expected
      // Away from the boundaries (which the ray crosses from points offset by ~1e-4): the
      // collision's medium is the one at its distance, and per lane the weight is T_k/p_0 and the
      // ratio p_k/p_0, with p_k = σ_t(λ_k)·T_k the collision density.
      if (std::abs(t - std::round(t)) < 1e-3) continue;
      ASSERT_EQ(f.medium, mediumNamed(t >= 2.0 && t < 4.0 ? "inner" : "outer")) << "t = " << t;
      for (int k = 0; k < kLanes; ++k) {
        const double l = lambda[size_t(k)], p0 = sigmaAt(hero, t) * transmittance(hero, t);
        ASSERT_NEAR(f.weight[k], transmittance(l, t) / p0, 1e-3 * f.weight[k]) << "lane " << k << ", t = " << t;
        ASSERT_NEAR(f.ratio[k], sigmaAt(l, t) * transmittance(l, t) / p0, 1e-3 * f.ratio[k]) << "lane " << k;
      }
    }
    for (int b = 0; b < bins; ++b)
      expected[size_t(b)] = n * (transmittance(hero, 1.0 + 0.1 * b) - transmittance(hero, 1.0 + 0.1 * (b + 1)));
    expected[bins] = n * transmittance(hero, 5.0);
    EXPECT_GT(test::chi2PValue(observed, expected), 1e-3);
  }
}

// Lane k's collision probability in [a, b) is E[w_k·σ_t,k(x)·1{collision in [a, b)}] and its
// transmittance E[w_k·1{escape}], over lane 0's draws, for a fixed hero (each lane k is then
// sampled at lane 0's density, which is positive wherever lane k's is) and with the balance
// heuristic over a hero drawn uniformly among the lanes (w_k·misWeight, LaneRatios).
TEST_F(FreeFlightTest, EveryLaneEstimatesItsOwnCollisionDensityAndTransmittance) {
  const int cells = 9, n = 40000;  // 8 intervals of 0.5 over [1, 5), then escape
  struct Accumulator {
    double sum[kLanes][cells] = {}, sq[kLanes][cells] = {};
    void add(int lane, int cell, double v) { sum[lane][cell] += v, sq[lane][cell] += v * v; }
  };
  Accumulator fixedHero, balance;
  Rng rng(77, 1);
  for (int i = 0; i < n; ++i) {
    const int hero = i % kLanes;  // the strata are symmetric: every lane is the hero as often
    std::array<float, kLanes> lambda;
    for (int j = 0; j < kLanes; ++j) lambda[size_t(j)] = kLambdas[size_t((hero + j) % kLanes)];
    const FreeFlight f = fly(lambda, rng.uniform());
    LaneRatios ratios;
    ratios.reset(kLanes);
    std::copy(f.ratio, f.ratio + kLanes, ratios.r);
    const double mis = ratios.misWeight();
    const double t = f.p.x + 3.0;
    const int cell = f.collided ? std::clamp(int((t - 1.0) / 0.5), 0, cells - 2) : cells - 1;
    for (int j = 0; j < kLanes; ++j) {
      const int lane = (hero + j) % kLanes;
      const double v = f.weight[j] * (f.collided ? sigmaAt(lambda[size_t(j)], t) : 1.0);
      // The plain estimator of lane 0 only: lanes of other heroes are in `balance`.
      if (hero == 0) fixedHero.add(lane, cell, v);
      balance.add(lane, cell, v * mis);
      if (!f.collided) {
        ASSERT_EQ(f.weight[j], f.ratio[j]) << "escape: T_k/P_0 = P_k/P_0";
      }
    }
  }
  const auto expectUnbiased = [&](const Accumulator& acc, double count, const char* name) {
    for (int lane = 0; lane < kLanes; ++lane)
      for (int c = 0; c < cells; ++c) {
        const double lambda = kLambdas[size_t(lane)];
        const double exact = c == cells - 1 ? transmittance(lambda, 5.0)
                                            : transmittance(lambda, 1.0 + 0.5 * c) - transmittance(lambda, 1.5 + 0.5 * c);
        const double mean = acc.sum[lane][c] / count;
        const double se = std::sqrt(std::max(0.0, acc.sq[lane][c] / count - mean * mean) / count);
        EXPECT_NEAR(mean, exact, 4.0 * se + 1e-6) << name << ": λ " << lambda << ", cell " << c;
      }
  };
  expectUnbiased(fixedHero, n / kLanes, "fixed hero");
  expectUnbiased(balance, n, "spectral MIS");
}

TEST_F(FreeFlightTest, ReachingASurfaceWeighsTheLanesByTheirTransmittanceRatio) {
  // From the centre (in "inner") along +y: inner over [0, 1), outer over [1, 2), vacuum to the
  // rectangle at y = 3. An optical depth beyond the path's: no collision.
  const std::array<float, kLanes> lambda = kLambdas;
  const FreeFlight f = fly(lambda, 0.9999f, Vec3(0.0f), Vec3(0, 1, 0), mediumNamed("inner"));
  ASSERT_FALSE(f.collided);
  ASSERT_TRUE(f.hit.has_value());
  EXPECT_EQ(f.hit->shape, 2u);
  EXPECT_NEAR(f.hit->p.y, 3.0f, 1e-4f);
  EXPECT_EQ(f.medium, -1);
  const auto tau = [](double l) { return sigmaInner(l) + sigmaOuter(l); };
  for (int k = 0; k < kLanes; ++k) {
    EXPECT_NEAR(f.weight[k], std::exp(tau(lambda[0]) - tau(lambda[size_t(k)])), 1e-4) << "lane " << k;
    EXPECT_EQ(f.weight[k], f.ratio[k]);
  }
}

TEST_F(FreeFlightTest, SegmentTransmittanceIsTheExponentialOfTheOpticalDepth) {
  const std::array<float, kLanes> lambda = kLambdas;
  float tr[kLanes];
  struct Segment {
    Vec3 origin, d;
    float tMax;
    const char* medium;  // "" for vacuum
    double (*tau)(double);
  };
  const Segment segments[] = {
      // Through both spheres and out.
      {Vec3(-3, 0, 0), Vec3(1, 0, 0), 10.0f, "", [](double l) { return opticalDepth(l, 10.0); }},
      // Ending inside the inner sphere.
      {Vec3(-3, 0, 0), Vec3(1, 0, 0), 3.5f, "", [](double l) { return opticalDepth(l, 3.5); }},
      // From inside the inner sphere to inside the outer one.
      {Vec3(0, 0, 0), Vec3(0, 0, -1), 1.5f, "inner", [](double l) { return sigmaInner(l) + 0.5 * sigmaOuter(l); }},
      // Outside every medium: nothing attenuates.
      {Vec3(-3, 0, 0), Vec3(-1, 0, 0), 5.0f, "", [](double) { return 0.0; }},
  };
  for (const Segment& s : segments) {
    ASSERT_TRUE(segmentTransmittance(*scene, s.origin, s.d, s.tMax, *s.medium ? mediumNamed(s.medium) : -1, lambda,
                                     tr, counter));
    for (int k = 0; k < kLanes; ++k)
      EXPECT_NEAR(tr[k], std::exp(-s.tau(lambda[size_t(k)])), 2e-5) << "tMax " << s.tMax << ", lane " << k;
  }
  // The rectangle at y = 3 blocks a segment that reaches it, not one that stops short.
  EXPECT_TRUE(segmentTransmittance(*scene, Vec3(0.0f), Vec3(0, 1, 0), 2.9f, mediumNamed("inner"), lambda, tr, counter));
  EXPECT_NEAR(tr[0], std::exp(-(sigmaInner(lambda[0]) + sigmaOuter(lambda[0]))), 2e-5);
  EXPECT_FALSE(segmentTransmittance(*scene, Vec3(0.0f), Vec3(0, 1, 0), 3.1f, mediumNamed("inner"), lambda, tr, counter));
}

// The medium a direction leaves into from a vertex: a boundary's side (interior against the
// normal), the current medium through a shape without media, and a medium point's own medium.
// Shadow rays start in it: from a surface vertex on the inner sphere, outwards and inwards.
TEST_F(FreeFlightTest, ShadowRaysLeaveIntoTheMediumOnTheirSide) {
  const int inner = mediumNamed("inner"), outer = mediumNamed("outer");
  const std::optional<Hit> innerHit = scene->accel->intersect(Ray{Vec3(-1.5f, 0, 0), Vec3(1, 0, 0)});
  ASSERT_TRUE(innerHit.has_value());
  ASSERT_NEAR(innerHit->p.x, -1.0f, 1e-4f);
  const VertexMedium onInner{outer, true};
  EXPECT_EQ(onInner.leaving(*scene, *innerHit, Vec3(1, 0, 0)), inner);
  EXPECT_EQ(onInner.leaving(*scene, *innerHit, Vec3(-1, 0, 0)), outer);
  const std::optional<Hit> wall = scene->accel->intersect(Ray{Vec3(0, 2.5f, 0), Vec3(0, 1, 0)});
  ASSERT_TRUE(wall.has_value());  // the rectangle: no media, the ray stays where it was
  EXPECT_EQ((VertexMedium{-1, true}).leaving(*scene, *wall, Vec3(0, -1, 0)), -1);
  EXPECT_EQ((VertexMedium{inner, false}).leaving(*scene, *innerHit, Vec3(-1, 0, 0)), inner);

  // A light 1.5 beyond the inner sphere's surface at x = −1, seen from it: outwards through 1 of
  // outer and 0.5 of vacuum; inwards (light at x = 0.5) through 1.5 of inner.
  const std::array<float, kLanes> lambda = kLambdas;
  float tr[kLanes];
  LightSample out;
  out.wi = Vec3(-1, 0, 0), out.dist = 1.5f;
  ASSERT_TRUE(lightTransmittance(*scene, *innerHit, onInner, out, lambda, tr, counter));
  for (int k = 0; k < kLanes; ++k) EXPECT_NEAR(tr[k], std::exp(-sigmaOuter(lambda[size_t(k)])), 1e-4) << k;
  LightSample in;
  in.wi = Vec3(1, 0, 0), in.dist = 1.5f;
  ASSERT_TRUE(lightTransmittance(*scene, *innerHit, onInner, in, lambda, tr, counter));
  for (int k = 0; k < kLanes; ++k) EXPECT_NEAR(tr[k], std::exp(-1.5 * sigmaInner(lambda[size_t(k)])), 1e-4) << k;
}

}  // namespace
}  // namespace kasha
