// traceFreeFlight's weights against the transmittance they estimate (integrators/medium_transport.h):
// over u uniform in [0, 1), a flight through an index-matched fluorescent sphere of radius 1
// (chord 2) must give, per lane k, E[w_k·1{past}] = T_k = e^{−2σ_k} and E[w_k·1{collision}] =
// ∫₀² e^{−σ_k s} ds = (1 − e^{−2σ_k})/σ_k, with σ_k = σ_t(λ_k) from the medium's own spectra. Camera
// paths (Radiance) draw from the source-seeking mixture, light paths (Importance) analogously; both
// must be unbiased, and camera paths at a wavelength the medium hardly absorbs must still collide
// (docs/media-scenes.md, "Path tracing in fluorescent media").
#include <gtest/gtest.h>

#include <cmath>

#include "integrators/medium_transport.h"
#include "scene/scene_loader.h"

namespace kasha {
namespace {

// σ_a 0.05 everywhere; the fluorophore absorbs around 450 nm (peak 2) and emits around 600 nm.
constexpr const char* kScene = R"({
  "camera": {"position": [0, 0, -5], "look_at": [0, 0, 0], "fov": 30, "resolution": [4, 4]},
  "media": {"ink": {"type": "homogeneous", "sigma_a": 0.05,
            "fluorophores": [{"sigma_f": {"type": "gaussian", "center": 450, "fwhm": 40, "peak": 2},
                              "emission": {"type": "gaussian", "center": 600, "fwhm": 40}, "yield": 0.8}]}},
  "materials": {"white": {"type": "lambertian", "reflectance": 0.5}},
  "shapes": [{"type": "sphere", "center": [0, 0, 0], "radius": 1, "interior": "ink"}],
  "lights": [{"type": "point", "position": [0, 3, 0], "intensity": 1}]
})";

struct Moments {
  double past[3] = {}, collided[3] = {}, collisionShare = 0.0;
};

Moments integrate(const Scene& scene, TransportMode mode, const float* lambda) {
  constexpr int kN = 200000;  // midpoint rule over u
  Moments m;
  RayCounter counter;
  for (int i = 0; i < kN; ++i) {
    const float u = (float(i) + 0.5f) / float(kN);
    const FreeFlight f = traceFreeFlight(scene, Ray{Vec3(0, 0, -5), Vec3(0, 0, 1)}, -1, {lambda, 3}, u, mode, counter);
    for (int k = 0; k < 3; ++k) (f.collided ? m.collided : m.past)[k] += double(f.weight[k]) / kN;
    if (f.collided) m.collisionShare += 1.0 / kN;
  }
  return m;
}

TEST(FreeFlightMixture, WeightsEstimateTheTransmittanceForBothModes) {
  const auto scene = loadSceneFromString(kScene, "free_flight.json");
  const Medium& ink = *scene->media[0];
  const float lambda[3] = {600.0f, 450.0f, 520.0f};  // the hero hardly absorbed, then strongly, then between
  for (const TransportMode mode : {TransportMode::Radiance, TransportMode::Importance}) {
    const Moments m = integrate(*scene, mode, lambda);
    for (int k = 0; k < 3; ++k) {
      const double sigma = ink.sigmaT(lambda[k]);
      const double past = std::exp(-2.0 * sigma), collided = (1.0 - past) / sigma;
      EXPECT_NEAR(m.past[k], past, 2e-3 * past + 1e-4) << toString(mode) << " lane " << k;
      EXPECT_NEAR(m.collided[k], collided, 2e-3 * collided) << toString(mode) << " lane " << k;
    }
    // At 600 nm σ_t = 0.05 collides 1 − e^{−0.1} ≈ 10% of analog flights; the fluorescent source
    // rate there (Y·ê(600)·∫σ_f ≈ 1.6) makes camera paths collide far more often.
    if (mode == TransportMode::Radiance) EXPECT_GT(m.collisionShare, 0.4);
    else EXPECT_NEAR(m.collisionShare, 1.0 - std::exp(-2.0 * ink.sigmaT(lambda[0])), 1e-3);
  }
}

}  // namespace
}  // namespace kasha
