// The blend of two materials (materials/blend.h): its value and densities against the weighted
// sums of its components' own, evaluated through the components' Bsdfs directly; χ² of its
// samples against its densities (a constant and a textured weight, an elastic and a fluorescent
// component); a delta component's samples keep their own path weight and are reported specular;
// and bad blends are one-line errors.
#include <gtest/gtest.h>

#include <cmath>

#include "core/error.h"
#include "materials/material_json.h"
#include "tests/expect_contains.h"
#include "tests/material_chi2.h"
#include "tests/material_support.h"

namespace kasha {
namespace {

using nlohmann::json;

const WavelengthRange kRange{380.0f, 780.0f};
const TransportMode kModes[] = {TransportMode::Radiance, TransportMode::Importance};

const json kDiffuse = {{"type", "lambertian"},
                       {"reflectance", {{"type", "tabulated"}, {"wavelengths", {400, 700}}, {"values", {0.2, 0.8}}}}};
const json kMetal = {{"type", "rough_conductor"}, {"reflectance", 0.8}, {"alpha", 0.3}};
const json kJung = json::parse(R"({"type": "jung_fluorescent", "absorption": {"type": "gaussian", "center": 450,
  "fwhm": 80, "peak": 0.9}, "emission": {"type": "gaussian", "center": 540, "fwhm": 40}, "reflectance": 0.7,
  "c": 0.6, "Q": 0.8})");
const json kMirror = {{"type", "mirror"}, {"reflectance", 0.9}};

std::unique_ptr<Material> material(const json& v) {
  return parseMaterial(v, SpectrumContext("test.json", "."), "/materials/m", kRange);
}
json blendJson(const json& first, const json& second, double weight) {
  return {{"type", "blend"}, {"weight", weight}, {"materials", {first, second}}};
}

// f = (1 − w)·f_0 + w·f_1 per lobe; the spectral stage's probability and density are the
// weighted sums of the components'; the direction density is Σ π_c·p_c with π_c ∝ a_c over the
// components having the lobe; and for two elastic components the event density is Mitsuba's
// mixture (1 − w)·pdf_0 + w·pdf_1 of the components' whole densities.
TEST(Blend, ValueAndDensitiesAreTheWeightedSumsOfTheComponents) {
  const float w = 0.3f;
  for (const auto& [first, second] : {std::pair{kDiffuse, kMetal}, {kJung, kMetal}}) {
    const auto blend = material(blendJson(first, second, w));
    const auto m0 = material(first), m1 = material(second);
    const Bsdf b = test::localBsdf(*blend), b0 = test::localBsdf(*m0), b1 = test::localBsdf(*m1);
    const bool fluorescent0 = b0.has(BsdfFlags::Fluorescent);
    ASSERT_EQ(b.has(BsdfFlags::Fluorescent), fluorescent0);
    Rng rng(5);
    int positive = 0;
    for (const TransportMode mode : kModes)
      for (int k = 0; k < 300; ++k) {
        const float cosKnown = 0.05f + 0.95f * rng.uniform(), phiKnown = 6.28f * rng.uniform();  // in this order
        const Vec3 wKnown = test::dirFromCosPhi(cosKnown, phiKnown);
        const Vec3 wOther = test::randomDirection(rng);
        const float lKnown = 400.0f + 300.0f * rng.uniform(), lOther = 400.0f + 300.0f * rng.uniform();
        EXPECT_NEAR(b.fluorescenceProbability(mode, lKnown),
                    (1 - w) * b0.fluorescenceProbability(mode, lKnown) + w * b1.fluorescenceProbability(mode, lKnown), 1e-6f);
        for (const SpectralLobe lobe : {SpectralLobe::Elastic, SpectralLobe::Fluorescent}) {
          const test::Event e = test::physical(mode, wKnown, lKnown, wOther, lobe == SpectralLobe::Elastic ? lKnown : lOther);
          const float f0 = b0.eval({mode, lobe, e.lambdaIn, e.lambdaOut}, e.wi, e.wo),
                      f1 = b1.eval({mode, lobe, e.lambdaIn, e.lambdaOut}, e.wi, e.wo);
          const float f = b.eval({mode, lobe, e.lambdaIn, e.lambdaOut}, e.wi, e.wo);
          EXPECT_TRUE(test::close(f, (1 - w) * f0 + w * f1, 1e-5, 1e-7));
          positive += f > 0.0f;
          const float lOth = lobe == SpectralLobe::Elastic ? lKnown : lOther;
          const float s0 = b0.spectralPdf(mode, lKnown, lOth, lobe), s1 = b1.spectralPdf(mode, lKnown, lOth, lobe);
          EXPECT_TRUE(test::close(b.spectralPdf(mode, lKnown, lOth, lobe), (1 - w) * s0 + w * s1, 1e-5, 1e-8));
          // π_c: both components for the elastic lobe, the fluorescent one alone for the fluorescent lobe.
          const float pi0 = lobe == SpectralLobe::Elastic ? 1 - w : (fluorescent0 ? 1.0f : 0.0f);
          const float d0 = b0.directionPdf({mode, lobe, e.lambdaIn, e.lambdaOut}, wKnown, wOther);
          const float d1 = b1.directionPdf({mode, lobe, e.lambdaIn, e.lambdaOut}, wKnown, wOther);
          const float direction = pi0 * d0 + (1 - pi0) * d1;
          EXPECT_TRUE(test::close(b.directionPdf({mode, lobe, e.lambdaIn, e.lambdaOut}, wKnown, wOther), direction,
                                  1e-5, 1e-8));
          const ScatterDensity d = b.pdf({mode, lobe, e.lambdaIn, e.lambdaOut}, e.wi, e.wo);
          EXPECT_TRUE(test::close(d.pdf, ((1 - w) * s0 + w * s1) * direction, 1e-4, 1e-8));
          if (!fluorescent0 && lobe == SpectralLobe::Elastic) {
            const ScatterDensity p0 = b0.pdf({mode, lobe, e.lambdaIn, e.lambdaOut}, e.wi, e.wo),
                                 p1 = b1.pdf({mode, lobe, e.lambdaIn, e.lambdaOut}, e.wi, e.wo);
            EXPECT_TRUE(test::close(d.pdf, (1 - w) * p0.pdf + w * p1.pdf, 1e-5, 1e-8));
            EXPECT_TRUE(test::close(d.pdfRev, (1 - w) * p0.pdfRev + w * p1.pdfRev, 1e-5, 1e-8));
          }
        }
      }
    EXPECT_GT(positive, 200) << "the comparison saw nonzero values";
  }
}

// Joint (lobe, direction, wavelength) χ² of the blend's samples against its densities: diffuse +
// rough conductor at w = 0.3, Jung's fluorescent material + rough conductor, and a weight
// textured by a checkerboard (read at two texture coordinates, one per colour).
TEST(Blend, SamplesFollowTheirDensities) {
  test::Chi2Config cfg;
  cfg.range = kRange;
  cfg.samples = 100000;
  cfg.subDir = 6;  // the conductor's lobe is peaked: a finer quadrature of the expected counts
  cfg.rejectionCell = true;  // the conductor's lobe reaches below the surface
  json textured = blendJson(kDiffuse, kMetal, 1.0);
  textured["weight_texture"] = {{"type", "checkerboard"}, {"color0", 0.9}, {"color1", 0.2}};
  const auto plain = material(blendJson(kDiffuse, kMetal, 0.3)), fluorescent = material(blendJson(kJung, kMetal, 0.4));
  const auto checker = material(textured);
  ASSERT_TRUE(checker->textured());
  struct Case {
    const Bsdf bsdf;
    float lambda;
  };
  const Case cases[] = {{test::localBsdf(*plain, 550.0f), 550.0f},
                        {test::localBsdf(*fluorescent, 450.0f), 450.0f},
                        {test::localBsdf(*fluorescent, 560.0f), 560.0f},
                        {test::localBsdf(*checker, 600.0f, Vec2(0.25f, 0.25f)), 600.0f},
                        {test::localBsdf(*checker, 600.0f, Vec2(0.75f, 0.25f)), 600.0f}};
  uint64_t seed = 3;
  for (const Case& c : cases)
    for (const TransportMode mode : kModes) {
      const Vec3 w = glm::normalize(Vec3(0.3f, -0.2f, 0.6f));
      const test::Chi2Result r = test::jointChi2(c.bsdf, mode, w, c.lambda, seed++, cfg);
      EXPECT_GT(r.p, 1e-3) << toString(mode) << " λ = " << c.lambda;
    }
}

// Mirror and diffuse, a = 0.6 on the mirror: the mirror direction is drawn with probability 0.6,
// reported specular, with the mirror's own path weight R; the rest are the diffuse lobe's,
// weighted 1; away from the mirror direction the value and density are the diffuse's alone.
TEST(Blend, DeltaComponentKeepsItsOwnPathWeight) {
  const auto blend = material(blendJson(kMirror, {{"type", "lambertian"}, {"reflectance", 0.5}}, 0.4));
  EXPECT_FALSE(blend->flags() == BsdfFlags::DeltaDirection);
  const Bsdf b = test::localBsdf(*blend, 500.0f);
  EXPECT_FALSE(b.has(BsdfFlags::DeltaDirection));
  Rng rng(9);
  for (const TransportMode mode : kModes) {
    const int n = 20000;
    int specular = 0;
    for (int i = 0; i < n; ++i) {
      const float cosKnown = 0.1f + 0.9f * rng.uniform(), phiKnown = 6.28f * rng.uniform();  // in this order
      const Vec3 known = test::dirFromCosPhi(cosKnown, phiKnown);
      const std::optional<ScatterSample> s = b.sample(mode, known, 500.0f, Vec3{rng.uniform(), rng.uniform(), rng.uniform()});
      ASSERT_TRUE(s);
      const float weight = s->f * std::abs(s->w.z) / s->pdf;
      if (s->specular) {
        ++specular;
        EXPECT_EQ(s->w, Vec3(-known.x, -known.y, known.z));
        EXPECT_NEAR(weight, 0.9f, 1e-5f) << "the mirror's path weight";
        EXPECT_NEAR(s->pdf, 0.6f, 1e-6f);
      } else {
        EXPECT_NEAR(weight, 0.5f, 1e-4f) << "the diffuse lobe's path weight (ρ, cosine sampled)";
        EXPECT_NEAR(s->pdf, 0.4f * std::abs(s->w.z) / kPi, 1e-5f);
      }
    }
    const double p = 0.6, se = std::sqrt(p * (1 - p) / n);
    EXPECT_NEAR(double(specular) / n, p, 4 * se) << toString(mode);
    const Vec3 wo = test::dirFromCosPhi(0.7f, 1.0f), wi = test::dirFromCosPhi(0.4f, 2.5f);
    EXPECT_NEAR(b.eval({mode, SpectralLobe::Elastic, 500.0f, 500.0f}, wi, wo), 0.4f * 0.5f / kPi, 1e-6f);
  }
}

// Bad blends: not two materials, a weight outside [0, 1], a textured component, a component with
// both delta and smooth lobes; each an InputError naming the field.
TEST(Blend, BadBlendsAreErrors) {
  const auto error = [](const json& v) -> std::string {
    try {
      material(v);
    } catch (const InputError& e) {
      return e.what();
    }
    return "no error";
  };
  json one = blendJson(kDiffuse, kMetal, 0.5);
  one["materials"] = json::array({kDiffuse});  // (a braced single json is a copy under some compilers)
  EXPECT_CONTAINS(error(one), "/materials/m/materials: expected an array of two materials, got 1 materials");
  json three = one;
  three["materials"] = json::array({kDiffuse, kMetal, kMirror});
  EXPECT_CONTAINS(error(three), "got 3 materials");
  EXPECT_CONTAINS(error(blendJson(kDiffuse, kMetal, 1.5)), "/materials/m/weight: must lie in [0, 1]");
  EXPECT_CONTAINS(error(blendJson(kDiffuse, kMetal, -0.1)), "/materials/m/weight: must lie in [0, 1]");
  json textured = kDiffuse;
  textured["reflectance_texture"] = {{"type", "checkerboard"}, {"color0", 0.9}, {"color1", 0.2}};
  EXPECT_CONTAINS(error(blendJson(textured, kMetal, 0.5)), "a blend of a textured material is not supported");
  const json mask = {{"type", "mask"}, {"opacity", 0.5}, {"material", kDiffuse}};
  EXPECT_CONTAINS(error(blendJson(mask, kMetal, 0.5)), "both delta and smooth lobes (mask(lambertian))");
  EXPECT_CONTAINS(error(blendJson(blendJson(kMirror, kDiffuse, 0.5), kMetal, 0.5)), "both delta and smooth lobes");
  EXPECT_NO_THROW(material(blendJson(blendJson(kMirror, kMirror, 0.5), kMetal, 0.5)));  // all deltas
}

}  // namespace
}  // namespace kasha
