// Heterogeneous media (docs/media.md §4): delta tracking of free flights, with the lanes' null
// collisions in the spectral MIS, and ratio tracking of shadow rays, against an independent
// computation of the same scene: a density field that is 1 inside a sphere of radius r and 1/4
// elsewhere in a sphere of radius R renders as two nested homogeneous spheres (exact transmittance
// and collisions by optical depth) of the full and the quartered coefficients. The medium is
// chromatic (σ_t depends on λ, so the lanes' ratios differ; heterogeneous media do not fluoresce
// yet). pt with 4 lanes, pt with one, lt, bdpt and vcm (their weights with the flights' estimated
// optical depths, media.md §5) must each agree with pt on the nested spheres within 4σ per region,
// and ppm with ppm on the nested spheres.
#include <gtest/gtest.h>

#include <string>

#include "integrators/integrator_factory.h"
#include "scene/scene_loader.h"
#include "tests/integrator_names.h"
#include "tests/region_batches.h"
#include "tests/support.h"

namespace kasha {
namespace {

constexpr int kRes = 12, kRegions = 4;
constexpr float kInner = 0.45f, kOuter = 1.0f;

// The medium with its coefficients times `scale`: chromatic scattering (g = 0.4) and absorption.
std::string medium(float scale) {
  const auto s = [scale](float v) { return std::to_string(v * scale); };
  return R"({"type": "homogeneous", "g": 0.4,
    "sigma_s": {"type": "tabulated", "wavelengths": [400, 700], "values": [)" + s(3.0f) + ", " + s(0.8f) + R"(]},
    "sigma_a": {"type": "tabulated", "wavelengths": [400, 500, 550, 700], "values": [)" + s(1.5f) + ", " + s(1.0f) + ", " +
         s(0.3f) + ", " + s(0.3f) + R"(]}})";
}

// Nested spheres with homogeneous media, or (one medium, `heterogeneous`) the outer sphere alone,
// whose medium gets the density field below; over a white floor, under a square lamp.
std::unique_ptr<Scene> scene(bool heterogeneous) {
  const std::string spheres =
      heterogeneous ? R"({"type": "sphere", "center": [0, 1, 0], "radius": 1.0, "interior": "full"})"
                    : R"({"type": "sphere", "center": [0, 1, 0], "radius": 1.0, "interior": "quarter"},
                         {"type": "sphere", "center": [0, 1, 0], "radius": 0.45, "interior": "full", "exterior": "quarter"})";
  auto s = loadSceneFromString(R"({
    "wavelength_range": [400, 700],
    "render": {"spp": 1, "max_depth": 12},
    "camera": {"position": [0, 1.2, -4], "look_at": [0, 1, 0], "fov": 40, "resolution": [12, 12]},
    "materials": {"white": {"type": "lambertian", "reflectance": 0.7}},
    "media": {"full": )" + medium(1.0f) + R"(, "quarter": )" + medium(0.25f) + R"(},
    "shapes": [{"type": "rectangle", "center": [0, 0, 0], "u": [0, 0, 4], "v": [4, 0, 0], "material": "white"},
               {"type": "rectangle", "center": [0.5, 3, -0.5], "u": [0.6, 0, 0], "v": [0, 0, 0.6], "material": "white",
                "emission": {"radiance": {"type": "tabulated", "wavelengths": [400, 700], "values": [6, 3]},
                             "two_sided": true}},
               )" + spheres + R"(]
  })", heterogeneous ? "heterogeneous.json" : "nested.json");
  if (heterogeneous) {
    // Density 1 inside radius kInner of the centre, 1/4 elsewhere (the sphere bounds the medium).
    struct TwoLevels final : DensityField {
      float density(const Vec3& p) const override {
        return glm::length(p - Vec3(0, 1, 0)) < kInner ? 1.0f : 0.25f;
      }
      float maxDensity() const override { return 1.0f; }
      float extent(const Vec3&, const Vec3&) const override { return kInf; }  // bounded by the sphere
    };
    const Medium& full = *s->media[0];
    s->media[0] = std::make_unique<Medium>(full.name(), full.params(), full.range(), std::make_shared<TwoLevels>());
    s->mediumScattering[0] = std::make_unique<VolumeScattering>(*s->media[0]);
  }
  return s;
}

// Rows of the image in kRegions bands (the lamp's side of the sphere, its middle, the floor).
int band(int, int y) { return y * kRegions / kRes; }

std::vector<test::BatchStats> regions(const Scene& s, const std::string& name, int lanes, int spp,
                                      const PhotonMappingSettings& ppm = {}) {
  RenderSettings settings = s.render;
  settings.heroWavelengths = lanes;
  settings.ppm = ppm;
  const auto integrator = test::makeTestIntegrator(name, s, settings);
  return test::regionBatches(s, *integrator, kRes, kRes, kRegions, band, spp, 12, 7);
}

TEST(HeterogeneousMedia, DeltaAndRatioTrackingAgreeWithNestedHomogeneousMedia) {
  const auto nested = scene(false), tracked = scene(true);
  ASSERT_FALSE(nested->media[1]->heterogeneous());
  ASSERT_TRUE(tracked->media[0]->heterogeneous());
  const std::vector<test::BatchStats> reference = regions(*nested, "pt", 4, 64);
  struct Case {
    const char* name;
    int lanes, spp;
  };
  for (const Case& c : {Case{"pt", 4, 64}, Case{"pt", 1, 96}, Case{"lt", 4, 64}, Case{"bdpt", 1, 64}, Case{"vcm", 1, 64}}) {
    SCOPED_TRACE(std::string(c.name) + " with " + std::to_string(c.lanes) + " lanes");
    // Power: a combined standard error below 6% of a region, or 2% of the brightest.
    test::expectRegionsAgree(reference, regions(*tracked, c.name, c.lanes, c.spp), 4.0, 0.06, 0.02);
  }
}

// ppm's volume photons in the density field against ppm on the nested spheres: the same estimator
// (the same blur of the same radiance) on the same light, so they agree in expectation whatever
// the radii; the photons' fluxes must leave out the density at their own collision
// (photon_tracer.cpp; docs/photon-mapping.md §9). Keeping it in puts the quarter-density shell's
// photons at a quarter of their flux.
TEST(HeterogeneousMedia, VolumePhotonsAgreeWithNestedHomogeneousMedia) {
  const auto nested = scene(false), tracked = scene(true);
  PhotonMappingSettings ppm;
  ppm.photonsPerPass = 4096;
  ppm.radius = 0.1f;
  ppm.volumeRadius = 0.15f;
  // Power: a combined standard error below 6% of a region, or 2% of the brightest.
  test::expectRegionsAgree(regions(*nested, "ppm", 4, 32, ppm), regions(*tracked, "ppm", 4, 32, ppm), 4.0, 0.06, 0.02);
}

}  // namespace
}  // namespace kasha
