// Unit tests of the smooth mirror (materials/mirror.h): docs/validation.md §3 for a specular elastic
// lobe, whose direction density is the discrete probability 1 and whose value is the Dirac delta's
// coefficient R(λ)/|cos θ|.
#include <gtest/gtest.h>

#include <string>

#include "core/error.h"
#include "core/rng.h"
#include "materials/material_json.h"
#include "materials/mirror.h"
#include "tests/material_support.h"

namespace kasha {
namespace {

using test::close;
using test::randomDirection;

const WavelengthRange kRange{360.0f, 830.0f};

// Rises from 0.3 to 0.9 and is zero from 780 nm on (nothing reflected there).
Spectrum reflectance() {
  return Spectrum::piecewiseLinear({360.0f, 780.0f, 780.0f}, {0.3f, 0.9f, 0.0f});
}

// Physical order of an event sampled in `mode` from the known direction.
struct Event {
  Vec3 wi, wo;
};
Event physical(TransportMode mode, const Vec3& wKnown, const Vec3& wSampled) {
  return mode == TransportMode::Radiance ? Event{wSampled, wKnown} : Event{wKnown, wSampled};
}

TEST(MirrorSampling, ReflectsWithProbabilityOneAndWeightR) {
  const Mirror m(reflectance());
  Rng rng(3);
  int checked = 0;
  for (int i = 0; i < 20000; ++i) {
    const TransportMode mode = (i & 1) ? TransportMode::Radiance : TransportMode::Importance;
    const Vec3 wKnown = randomDirection(rng);
    const float l = kRange.min + rng.uniform() * kRange.width();
    const float r = m.reflectance()(l);
    const std::optional<ScatterSample> s = m.sample(mode, wKnown, l, Vec3(rng.uniform(), rng.uniform(), rng.uniform()));
    if (!s) {
      EXPECT_EQ(r, 0.0f) << "λ = " << l;
      continue;
    }
    ++checked;
    EXPECT_EQ(s->lobe, SpectralLobe::Elastic);
    EXPECT_EQ(s->lambda, l);
    EXPECT_TRUE(s->specular);
    EXPECT_EQ(s->w, Vec3(-wKnown.x, -wKnown.y, wKnown.z));
    EXPECT_EQ(s->pdf, 1.0f);
    EXPECT_EQ(s->pdfRev, 1.0f);
    EXPECT_TRUE(close(s->f * std::abs(s->w.z) / s->pdf, r, 1e-6));
    // sample() and pdf() agree, forward and reverse.
    const Event ev = physical(mode, wKnown, s->w);
    const ScatterDensity d = m.pdf({mode, SpectralLobe::Elastic, l, l}, ev.wi, ev.wo);
    EXPECT_EQ(d.pdf, s->pdf);
    EXPECT_EQ(d.pdfRev, s->pdfRev);
  }
  EXPECT_GT(checked, 15000);
}

TEST(MirrorEval, DeltaCoefficientAtTheMirrorDirectionOnly) {
  const Mirror m(reflectance());
  EXPECT_TRUE(has(m.flags(), BsdfFlags::DeltaDirection));
  EXPECT_FALSE(has(m.flags(), BsdfFlags::Fluorescent));
  Rng rng(5);
  for (int i = 0; i < 2000; ++i) {
    const Vec3 a = randomDirection(rng), other = randomDirection(rng);
    const Vec3 b(-a.x, -a.y, a.z);
    const float l = kRange.min + rng.uniform() * (780.0f - kRange.min);
    for (const TransportMode mode : {TransportMode::Radiance, TransportMode::Importance}) {
      // R/|cos θ|, the same in both modes (reflection keeps solid angle), reciprocal, two-sided.
      EXPECT_TRUE(close(m.eval({mode, SpectralLobe::Elastic, l, l}, a, b), m.reflectance()(l) / std::abs(a.z), 1e-6));
      EXPECT_EQ(m.eval({mode, SpectralLobe::Elastic, l, l}, a, b), m.eval({mode, SpectralLobe::Elastic, l, l}, b, a));
      EXPECT_EQ(m.eval({mode, SpectralLobe::Elastic, l, l}, a, b),
                m.eval({flip(mode), SpectralLobe::Elastic, l, l}, a, b));
      EXPECT_EQ(m.eval({mode, SpectralLobe::Fluorescent, l, l}, a, b), 0.0f);
      EXPECT_EQ(m.spectralPdf(mode, l, l, SpectralLobe::Fluorescent), 0.0f);
      // Any other direction: nothing, and no density.
      if (glm::dot(other, b) < 0.999f) {
        EXPECT_EQ(m.eval({mode, SpectralLobe::Elastic, l, l}, a, other), 0.0f);
        EXPECT_EQ(m.eval({mode, SpectralLobe::Elastic, l, l}, other, a), 0.0f);
        EXPECT_EQ(m.pdf({mode, SpectralLobe::Elastic, l, l}, a, other).pdf, 0.0f);
        EXPECT_EQ(m.pdf({mode, SpectralLobe::Elastic, l, l}, a, other).pdfRev, 0.0f);
      }
      // Transmission never happens: −b is on the other side.
      EXPECT_EQ(m.eval({mode, SpectralLobe::Elastic, l, l}, a, -b), 0.0f);
    }
  }
}

TEST(MirrorEval, MatchesDirectionsUpToRounding) {
  // A direction carried through frame changes is off by ~1e-7; one 0.02 rad away is another one.
  const Mirror m(Spectrum::constant(0.5f));
  const Vec3 wo = glm::normalize(Vec3(0.3f, -0.4f, 0.8f));
  const Vec3 mirror(-wo.x, -wo.y, wo.z);
  const Vec3 nudged = glm::normalize(mirror + Vec3(1e-4f, 0.0f, 0.0f));
  const Vec3 far = glm::normalize(mirror + Vec3(2e-2f, 0.0f, 0.0f));
  EXPECT_GT(m.eval({TransportMode::Radiance, SpectralLobe::Elastic, 500.0f, 500.0f}, nudged, wo), 0.0f);
  EXPECT_EQ(m.directionPdf({TransportMode::Radiance, SpectralLobe::Elastic, 500.0f, 500.0f}, wo, nudged), 1.0f);
  EXPECT_EQ(m.eval({TransportMode::Radiance, SpectralLobe::Elastic, 500.0f, 500.0f}, far, wo), 0.0f);
  EXPECT_EQ(m.directionPdf({TransportMode::Radiance, SpectralLobe::Elastic, 500.0f, 500.0f}, wo, far), 0.0f);
}

TEST(MirrorSampling, NothingReflectedGivesNoSample) {
  const Mirror m(reflectance());
  for (const TransportMode mode : {TransportMode::Radiance, TransportMode::Importance}) {
    EXPECT_FALSE(m.sample(mode, Vec3(0, 0, 1), 800.0f, Vec3(0.5f)));
    EXPECT_EQ(m.spectralPdf(mode, 800.0f, 800.0f, SpectralLobe::Elastic), 0.0f);
    // A grazing known direction has no mirror direction off the surface.
    EXPECT_FALSE(m.sampleDirection({mode, SpectralLobe::Elastic, 500.0f, 500.0f}, Vec3(1, 0, 0), Vec2(0.5f)));
  }
}

std::unique_ptr<Material> parse(const nlohmann::json& v) {
  const SpectrumContext ctx{"scene.json", ".", nullptr};
  return parseMaterial(v, ctx, "/materials/m", kRange);
}

std::string parseError(const nlohmann::json& v) {
  try {
    parse(v);
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

TEST(MirrorJson, ParsesAndRejectsBadReflectance) {
  const std::unique_ptr<Material> m = parse({{"type", "mirror"}, {"reflectance", 0.8}});
  ASSERT_NE(dynamic_cast<const Mirror*>(m.get()), nullptr);
  EXPECT_EQ(m->describe(), "mirror");
  const std::string tooBright = parseError({{"type", "mirror"}, {"reflectance", 1.2}});
  EXPECT_EQ(tooBright.rfind("scene.json: /materials/m/reflectance: reflectance 1.200000 exceeds 1", 0), 0u) << tooBright;
  EXPECT_EQ(parseError({{"type", "mirror"}}), "scene.json: /materials/m/reflectance: missing required field");
  EXPECT_EQ(parseError({{"type", "mirror"}, {"reflectance", 0.5}, {"ior", 1.5}}),
            "scene.json: /materials/m/ior: unknown field");
}

}  // namespace
}  // namespace kasha
