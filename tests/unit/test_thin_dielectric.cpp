// Unit tests of the thin dielectric slab (materials/thin_dielectric.h): its reflectance against
// the closed form at normal incidence, the two lobes' sampling against their probabilities, and
// the values in both transport modes. The lossless furnace is in test_specular_furnace.cpp.
#include <gtest/gtest.h>

#include <cmath>

#include "materials/specular_lobe.h"
#include "materials/thin_dielectric.h"
#include "tests/material_support.h"

namespace kasha {
namespace {

const WavelengthRange kRange{360.0f, 830.0f};

TEST(ThinDielectric, NormalIncidenceReflectanceIsTheSlabSeries) {
  // One face reflects F = ((n − 1)/(n + 1))² = 0.04 at n = 1.5; the slab F + (1−F)²F/(1−F²) = 2F/(1+F).
  const ThinDielectric slab(Ior::constant(1.5), kRange);
  const double F = 0.04;
  double series = F, inner = (1.0 - F) * (1.0 - F) * F;
  for (int k = 0; k < 40; ++k, inner *= F * F) series += inner;
  EXPECT_NEAR(slab.reflectance(1.0f, 550.0f), series, 1e-6);
  EXPECT_NEAR(series, 2.0 * F / (1.0 + F), 1e-12);
}

TEST(ThinDielectric, SamplesBothLobesWithTheirProbabilitiesFromBothSides) {
  const ThinDielectric slab(Ior::constant(1.5), kRange);
  for (const float side : {1.0f, -1.0f})
    for (const float c : {0.95f, 0.5f, 0.1f}) {
      const Vec3 w = test::dirFromCosPhi(side * c, 0.4f);
      const float R = slab.reflectance(c, 500.0f);
      int reflected = 0;
      constexpr int kN = 4000;
      for (int k = 0; k < kN; ++k) {
        const auto ds = slab.sampleDirection({TransportMode::Radiance, SpectralLobe::Elastic, 500.0f, 500.0f}, w,
                                             Vec2((float(k) + 0.5f) / kN, 0.5f));
        ASSERT_TRUE(ds && ds->specular);
        const bool reflect = specular::matches(ds->w, specular::reflect(w));
        EXPECT_TRUE(reflect || specular::matches(ds->w, -w)) << "straight through or mirrored";
        reflected += reflect;
        EXPECT_FLOAT_EQ(ds->pdf, reflect ? R : 1.0f - R);
        for (const TransportMode mode : {TransportMode::Radiance, TransportMode::Importance}) {
          // Path weight f·|cos|/pdf = 1 in both modes: lossless, no index change across the slab.
          const Vec3 wi = mode == TransportMode::Radiance ? ds->w : w, wo = mode == TransportMode::Radiance ? w : ds->w;
          const float f = slab.eval({mode, SpectralLobe::Elastic, 500.0f, 500.0f}, wi, wo);
          EXPECT_NEAR(f * std::abs(ds->w.z) / ds->pdf, 1.0f, 1e-5f);
          EXPECT_FLOAT_EQ(slab.directionPdf({mode, SpectralLobe::Elastic, 500.0f, 500.0f}, w, ds->w), ds->pdf);
        }
      }
      EXPECT_NEAR(double(reflected) / kN, R, 1.0 / kN + 1e-6);  // stratified u: exact to one sample
      // Nothing anywhere else.
      EXPECT_EQ(slab.eval({TransportMode::Radiance, SpectralLobe::Elastic, 500.0f, 500.0f},
                          test::dirFromCosPhi(0.3f, 1.0f), w),
                0.0f);
    }
}

}  // namespace
}  // namespace kasha
