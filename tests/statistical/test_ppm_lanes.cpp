// Wavelength lanes in ppm's photon pass (integrators/photon_mapping/photon_tracer.h,
// docs/photon-mapping.md §2): a photon holds up to kPhotonLanes lanes, more lanes are stored as
// several photons at the same vertex, and the estimate with such split photons still meets the
// closed form of the fluorescent furnace (docs/validation.md §1).
#include <gtest/gtest.h>

#include "integrators/photon_mapping/photon.h"
#include "integrators/photon_mapping/photon_tracer.h"
#include "scene/wavelength_strategy.h"
#include "tests/closed_form_support.h"

namespace kasha {
namespace {

constexpr int kLanes = 6;  // one full photon and one with two lanes at each vertex they all reach

TEST(PpmLanes, LanesBeyondARecordAreSplitAtTheSameVertex) {
  auto scene = test::load("furnace_overlap.json");
  const WavelengthStrategy light(scene->render.wavelengths.light, WavelengthSources(*scene), WavelengthSite::LightStart);
  PhotonTracing t;
  t.paths = 2000;
  t.lanes = kLanes;
  t.maxDepth = 4;
  t.memoryLimit = uint64_t(1) << 30;
  t.wavelengths = &light.density();
  RayCounter counter;
  const std::vector<Photon> photons = tracePhotons(*scene, t, 7, counter).surface;
  ASSERT_FALSE(photons.empty());
  size_t split = 0;
  for (size_t i = 0; i < photons.size(); ++i) {
    const Photon& ph = photons[i];
    ASSERT_GE(ph.lanes, 1);
    ASSERT_LE(ph.lanes, kPhotonLanes);
    for (int l = 0; l < ph.lanes; ++l) EXPECT_GT(ph.power[l], 0.0f);
    // A full photon is followed by the rest of its vertex's lanes, at the same place and depth.
    if (ph.lanes == kPhotonLanes && i + 1 < photons.size() && photons[i + 1].depth == ph.depth &&
        std::equal(ph.p, ph.p + 3, photons[i + 1].p)) {
      EXPECT_EQ(photons[i + 1].lanes, kLanes - kPhotonLanes);
      ++split;
    }
  }
  // In the furnace every lane survives (nothing is black), so nearly every vertex holds 6 lanes;
  // a fluorescent event gives 6 fresh lanes too.
  EXPECT_GT(split, photons.size() / 3);
}

TEST(PpmLanes, SplitPhotonsMeetTheFurnaceClosedForm) {
  auto scene = test::load("furnace_overlap.json");
  const test::Grid g(scene->range);
  const Vec3 exact = test::toXyz(g, test::furnaceClosedForm(g, test::jung(*scene), test::emissionOf(*scene)));
  RenderSettings s = scene->render;
  s.heroWavelengths = kLanes;
  s.maxDepth = 1000;
  test::expectXyzAgreement(*scene, "ppm", s, exact, 16, 256);
}

}  // namespace
}  // namespace kasha
