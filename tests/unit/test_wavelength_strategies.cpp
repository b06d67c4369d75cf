// Unit tests of the wavelength sampling strategies (scene/wavelength_strategy.h): the text form,
// each density's normalisation and sample/pdf consistency (χ²), Yamamoto's weights against a hand
// computation, unbiasedness of the MIS combinations on a 1-D integral, the fluorescent-event
// override, and the errors for strategies that do not apply.
#include <gtest/gtest.h>

#include <map>

#include "core/color.h"
#include "core/rng.h"
#include "scene/scene_loader.h"
#include "scene/wavelength_strategy.h"
#include "integrators/fluorescence_sampling.h"
#include "integrators/integrator_factory.h"
#include "tests/support.h"

namespace kasha {
namespace {

// Two fluorophores on two shapes of different area under a white-and-UV light pair.
// Fluorophore "one": c·a = 0.9 on [340, 400) nm, re-emitted Q·∫c·a = 0.8·54 = 43.2 spread over
// [500, 550) nm; "two": c·a = 0.25 on [400, 450) nm, re-emitted 0.5·12.5 = 6.25 over [600, 650) nm.
const char* kScene = R"({
  "wavelength_range": [300, 830],
  "camera": {"position": [0, 0, -5], "look_at": [0, 0, 0], "up": [0, 1, 0], "fov": 30, "resolution": [4, 4]},
  "materials": {
    "one": {"type": "jung_fluorescent", "absorption": {"type": "box", "min": 340, "max": 400, "value": 0.9},
            "emission": {"type": "box", "min": 500, "max": 550, "value": 1}, "reflectance": 0.5, "c": 1, "Q": 0.8},
    "two": {"type": "jung_fluorescent", "absorption": {"type": "box", "min": 400, "max": 450, "value": 0.5},
            "emission": {"type": "box", "min": 600, "max": 650, "value": 3}, "reflectance": 0.5, "c": 0.5, "Q": 0.5},
    "white": {"type": "lambertian", "reflectance": 0.5}
  },
  "shapes": [
    {"name": "ball", "type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "one"},
    {"name": "card", "type": "rectangle", "center": [0, -1, 0], "u": [2, 0, 0], "v": [0, 0, 2], "material": "two"},
    {"name": "wall", "type": "rectangle", "center": [0, 0, 3], "u": [3, 0, 0], "v": [0, 3, 0], "material": "white"}
  ],
  "lights": [
    {"type": "distant", "direction": [0, -1, 0.2], "irradiance": {"type": "gaussian", "center": 365, "fwhm": 10}},
    {"type": "environment", "radiance": {"type": "box", "min": 380, "max": 780, "value": 0.2}}
  ]
})";

std::unique_ptr<Scene> testScene() { return loadSceneFromString(kScene, "strategies.json"); }

WavelengthStrategy build(const std::string& spec, const WavelengthSources& src, WavelengthSite site, size_t m = 0) {
  return WavelengthStrategy(parseWavelengthSpec(spec), src, site, m);
}

// ∫ p over the range, midpoint rule on a 0.05 nm grid aligned with whole nanometres.
double integral(const WavelengthDensity& d, WavelengthRange r) {
  double s = 0.0;
  for (double l = r.min + 0.025; l < r.max; l += 0.05) s += d.pdf(float(l)) * 0.05;
  return s;
}

// χ² of 40 000 samples in 1 nm bins against the density's mass per bin; and sample() reports
// pdf(λ).
void expectSamplesFollowPdf(const WavelengthDensity& d, WavelengthRange r, uint64_t seed) {
  const int bins = int(r.width());
  std::vector<double> observed(size_t(bins), 0.0), expected(size_t(bins), 0.0);
  Rng rng(seed, 0);
  const int n = 40000;
  for (int i = 0; i < n; ++i) {
    const WavelengthSample s = d.sample(rng.uniform());
    ASSERT_GT(s.pdf, 0.0f);
    ASSERT_TRUE(r.contains(s.lambda)) << s.lambda;
    ASSERT_NEAR(s.pdf, d.pdf(s.lambda), 1e-5f * s.pdf) << s.lambda;
    observed[size_t(std::min(bins - 1, int(s.lambda - r.min)))] += 1.0;
  }
  for (int b = 0; b < bins; ++b) {
    double mass = 0.0;
    for (int k = 0; k < 20; ++k) mass += d.pdf(r.min + float(b) + (float(k) + 0.5f) / 20.0f) / 20.0;
    expected[size_t(b)] = mass * n;
  }
  EXPECT_GT(test::chi2PValue(observed, expected), 1e-3);
}

TEST(WavelengthSpec, ParsesEveryForm) {
  const WavelengthSpec a = parseWavelengthSpec("cmf");
  EXPECT_EQ(a.combination, WavelengthSpec::Combination::Single);
  ASSERT_EQ(a.components.size(), 1u);
  EXPECT_EQ(a.components[0].kind, WavelengthSpec::Kind::ColorMatching);
  const WavelengthSpec b = parseWavelengthSpec("mix:light@3,yamamoto=0.25");
  EXPECT_EQ(b.combination, WavelengthSpec::Combination::Mixture);
  ASSERT_EQ(b.components.size(), 2u);
  EXPECT_EQ(b.components[0].weight, 3.0f);
  EXPECT_EQ(b.components[1].kind, WavelengthSpec::Kind::Yamamoto);
  EXPECT_EQ(b.components[1].yamamotoWF, 0.25f);
  EXPECT_EQ(parseWavelengthSpec("os-power:cmf,uniform").combination, WavelengthSpec::Combination::OneSamplePower);
  EXPECT_EQ(parseWavelengthSpec("ms-balance:cmf,uniform").combination, WavelengthSpec::Combination::MultiBalance);
  EXPECT_EQ(parseWavelengthSpec("ms-power:cmf,light,emission").components.size(), 3u);
  EXPECT_TRUE(parseWavelengthSpec("mix:cmf,uniform").isDensity());
  EXPECT_FALSE(parseWavelengthSpec("ms-power:cmf,uniform").isDensity());
}

TEST(WavelengthSpec, RejectsMalformedText) {
  const std::map<std::string, std::string> bad = {
      {"spectral", "unknown kind 'spectral'"},
      {"max:cmf,uniform", "unknown combination 'max'"},
      {"cmf,uniform", "a list needs a combination"},
      {"mix:cmf", "at least two components"},
      {"mix:cmf,", "empty component"},
      {"cmf@2", "needs a combination"},
      {"mix:cmf@0,uniform", "weights must be positive"},
      {"mix:cmf@x,uniform", "weight 'x' is not a number"},
      {"yamamoto=1.5", "w_F must lie in [0, 1]"},
      {"light=0.5", "only yamamoto takes a value"},
      {"mix:material,uniform", "'material' cannot be combined"},
      {"", "empty component"},
  };
  for (const auto& [text, reason] : bad) {
    try {
      parseWavelengthSpec(text);
      ADD_FAILURE() << "accepted '" << text << "'";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(reason), std::string::npos) << e.what();
    }
  }
}

TEST(WavelengthStrategy, YamamotoFluorophoreWeightsByHand) {
  // w_Ft ∝ A_t·k_Ft: areas 2 and 1, integrals 3 and 4 → 6/10 and 4/10.
  const std::vector<float> w = yamamotoFluorophoreWeights({2.0f, 1.0f}, {3.0f, 4.0f});
  ASSERT_EQ(w.size(), 2u);
  EXPECT_FLOAT_EQ(w[0], 0.6f);
  EXPECT_FLOAT_EQ(w[1], 0.4f);

  // In the scene: p_F(λ) = Σ A_t·F_t(λ) / Σ A_t·k_t with the re-emitted spectra of kScene.
  const auto scene = testScene();
  const WavelengthSources src(*scene);
  ASSERT_EQ(src.fluorophores.size(), 2u);
  const float A1 = 4.0f * kPi, A2 = scene->shapes[1].area;
  EXPECT_NEAR(src.fluorophores[0].area, A1, 1e-4f * A1);
  EXPECT_NEAR(src.fluorophores[1].area, A2, 1e-4f * A2);
  const float w1 = A1 * 43.2f / (A1 * 43.2f + A2 * 6.25f);
  const WavelengthDensity emission = yamamotoFluorophoreDensity(src, false, src.seen);
  EXPECT_NEAR(emission.pdf(525.0f), w1 / 50.0f, 1e-4f * w1);
  EXPECT_NEAR(emission.pdf(625.0f), (1.0f - w1) / 50.0f, 1e-4f);
  // Yamamoto's mixture with w_F = 0.3: 0.3·p_F + 0.7·p_L, p_L the lights' power spectrum.
  const WavelengthStrategy y = build("yamamoto=0.3", src, WavelengthSite::Sensor);
  const SpectralDistribution lightSeen(src.lightPower, src.seen);
  auto lightPdf = [&](float l) { return lightSeen.pdf(l); };
  for (float l : {365.0f, 525.0f, 625.0f, 700.0f})
    EXPECT_NEAR(y.density().pdf(l), 0.3f * emission.pdf(l) + 0.7f * lightPdf(l), 1e-6f) << l;
  // For an excitation wavelength p_F follows what the fluorophores absorb: Σ A_t·c·a_t / Σ A_t·∫c·a_t.
  const WavelengthDensity absorbed = yamamotoFluorophoreDensity(src, true, src.range);
  const float wa1 = A1 * 54.0f / (A1 * 54.0f + A2 * 12.5f);
  EXPECT_NEAR(absorbed.pdf(370.0f), wa1 / 60.0f, 1e-4f * wa1 / 60.0f);
  EXPECT_NEAR(absorbed.pdf(420.0f), (1.0f - wa1) / 50.0f, 1e-4f / 50.0f);
  const WavelengthStrategy ya = build("yamamoto=0.4", src, WavelengthSite::LightStart);
  EXPECT_NEAR(ya.density().pdf(420.0f), 0.4f * absorbed.pdf(420.0f) + 0.6f * SpectralDistribution(src.lightPower, src.range).pdf(420.0f), 1e-6f);
}

TEST(WavelengthStrategy, EveryDensityIsNormalisedAndSampledAsItsPdf) {
  const auto scene = testScene();
  const WavelengthSources src(*scene);
  uint64_t seed = 1;
  // cmf alone cannot start light subpaths here: it misses the UV light below 360 nm.
  for (const char* spec : {"uniform", "cmf", "light", "yamamoto", "yamamoto=0.8", "mix:cmf,light@2,emission"}) {
    for (WavelengthSite site : {WavelengthSite::Sensor, WavelengthSite::LightStart}) {
      SCOPED_TRACE(std::string(spec) + " at " + toString(site));
      if (spec == std::string("cmf") && site == WavelengthSite::LightStart) continue;
      const WavelengthStrategy s = build(spec, src, site);
      const WavelengthRange r = site == WavelengthSite::Sensor ? src.seen : src.range;
      EXPECT_NEAR(integral(s.density(), r), 1.0, 2e-3);
      expectSamplesFollowPdf(s.density(), r, seed++);
    }
  }
  // At a fluorescent event "absorption" is the vertex's own c·a(λ), normalised.
  for (size_t m : {size_t(0), size_t(1)}) {
    SCOPED_TRACE("absorption of material " + std::to_string(m));
    const WavelengthStrategy s = build("absorption", src, WavelengthSite::Fluorescence, m);
    EXPECT_NEAR(integral(s.density(), src.range), 1.0, 2e-3);
    EXPECT_NEAR(s.density().pdf(m == 0 ? 370.0f : 425.0f), m == 0 ? 1.0f / 60.0f : 1.0f / 50.0f, 1e-6f);
    expectSamplesFollowPdf(s.density(), src.range, seed++);
  }
}

// E[Σ_i weight_i·g(λ_i)] = ∫g for every combination: the MIS weights partition unity.
TEST(WavelengthStrategy, MisCombinationsAreUnbiasedOnAnIntegral) {
  const auto scene = testScene();
  const WavelengthSources src(*scene);
  const Observer& o = Observer::cie1931();
  auto g = [&](float l) { return double(o.ybar(l) + 0.3f * o.zbar(l)) * (1.0 + double(src.reachable(l))); };
  double exact = 0.0;
  for (double l = src.seen.min + 0.025; l < src.seen.max; l += 0.05) exact += g(float(l)) * 0.05;
  uint64_t seed = 100;
  for (const char* spec : {"cmf", "mix:cmf,light@0.5", "os-power:cmf,light", "os-power:uniform@2,yamamoto",
                           "ms-balance:cmf,light", "ms-power:cmf,light,uniform"}) {
    SCOPED_TRACE(spec);
    const WavelengthStrategy s = build(spec, src, WavelengthSite::Sensor);
    Rng rng(seed++, 0);
    std::vector<double> batches;
    for (int b = 0; b < 16; ++b) {
      double sum = 0.0;
      const int n = 4000;
      for (int k = 0; k < n; ++k)
        for (int i = 0; i < s.samplesPerEstimate(); ++i) {
          const WavelengthStrategy::Draw d = s.draw(i, rng.uniform());
          if (d.weight > 0.0f) sum += d.weight * g(d.lambda);
        }
      batches.push_back(sum / n);
    }
    const test::BatchStats st = test::batchStats(batches);
    EXPECT_LT(st.stderr_, 0.01 * exact);
    EXPECT_NEAR(st.mean, exact, 4.0 * st.stderr_) << "mean " << st.mean << " ± " << st.stderr_;
  }
}

TEST(FluorescenceSampling, OverridesOnlyTheExcitationWavelength) {
  const auto scene = testScene();
  const WavelengthSources src(*scene);
  const Bsdf one = scene->materials[0]->bsdf(HitContext{});
  const FluorescenceSampling own(parseWavelengthSpec("material"), src, scene->materials.size());
  const FluorescenceSampling absorption(parseWavelengthSpec("absorption"), src, scene->materials.size());
  const FluorescenceSampling mixed(parseWavelengthSpec("mix:absorption,uniform"), src, scene->materials.size());
  // "absorption" is the material's own density (λ_i ∝ a) through the override.
  for (float lo : {525.0f, 450.0f})
    for (float li : {350.0f, 399.0f, 420.0f})
      for (SpectralLobe lobe : {SpectralLobe::Elastic, SpectralLobe::Fluorescent}) {
        const float lambdaIn = lobe == SpectralLobe::Elastic ? lo : li;
        EXPECT_NEAR(absorption.pdf(one, 0, lo, lambdaIn, lobe), own.pdf(one, 0, lo, lambdaIn, lobe), 1e-6f);
      }
  // Sampled events report the density pdf() gives them; the fluorescent lobe keeps P_c.
  Rng rng(5, 0);
  int fluorescent = 0;
  const int n = 20000;
  for (int i = 0; i < n; ++i) {
    const SpectralChoice c = mixed.sample(one, 0, 525.0f, rng.uniform());
    ASSERT_GT(c.pdf, 0.0f);
    EXPECT_NEAR(c.pdf, mixed.pdf(one, 0, 525.0f, c.lambda, c.lobe), 1e-5f * c.pdf);
    if (c.lobe == SpectralLobe::Fluorescent) {
      ++fluorescent;
      EXPECT_TRUE(src.range.contains(c.lambda));
    } else {
      EXPECT_EQ(c.lambda, 525.0f);
    }
  }
  const double pc = one.fluorescenceProbability(TransportMode::Radiance, 525.0f);
  EXPECT_NEAR(double(fluorescent) / n, pc, 4.0 * std::sqrt(pc * (1.0 - pc) / n));
  // The non-fluorescent material is left to its own sampling.
  const Bsdf white = scene->materials[2]->bsdf(HitContext{});
  const SpectralChoice w = mixed.sample(white, 2, 525.0f, 0.3f);
  EXPECT_EQ(w.lobe, SpectralLobe::Elastic);
  EXPECT_FLOAT_EQ(w.pdf, white.spectralPdf(TransportMode::Radiance, 525.0f, 525.0f, SpectralLobe::Elastic));
}

void expectStrategyError(const std::function<void()>& f, WavelengthSite site, const std::string& reason) {
  try {
    f();
    ADD_FAILURE() << "no error; expected '" << reason << "'";
  } catch (const WavelengthStrategyError& e) {
    EXPECT_EQ(e.site(), site);
    EXPECT_NE(std::string(e.what()).find(reason), std::string::npos) << e.what();
  }
}

TEST(WavelengthStrategy, RejectsStrategiesThatWouldBeBiasedOrDoNotApply) {
  const auto scene = testScene();
  const WavelengthSources src(*scene);
  // Light power covers every wavelength that reaches the sensor here (the fluorescence lies inside
  // the white light's 380–780 nm); the fluorophores' emission alone misses the white light.
  EXPECT_NO_THROW(build("light", src, WavelengthSite::Sensor));
  expectStrategyError([&] { build("emission", src, WavelengthSite::Sensor); }, WavelengthSite::Sensor,
                      "has density 0 at 360 nm");
  // At a fluorescent event of "two" (absorbing 400–450 nm) the white light covers the absorption;
  // at the light start an absorption density misses the lights' visible power.
  EXPECT_NO_THROW(build("light", src, WavelengthSite::Fluorescence, 1));
  expectStrategyError([&] { build("absorption", src, WavelengthSite::LightStart); }, WavelengthSite::LightStart,
                      "has density 0 at");
  expectStrategyError([&] { build("material", src, WavelengthSite::Sensor); }, WavelengthSite::Sensor,
                      "applies only to fluorescent events");
  expectStrategyError([&] { build("ms-balance:cmf@2,uniform", src, WavelengthSite::Sensor); },
                      WavelengthSite::Sensor, "weights '@' do not apply");
  expectStrategyError(
      [&] { FluorescenceSampling(parseWavelengthSpec("os-power:absorption,uniform"), src, scene->materials.size()); },
      WavelengthSite::Fluorescence, "needs one density");

  // Integrators reject strategies at sites they never draw, and non-densities where their MIS
  // weights need the density.
  auto with = [&](const char* sensor, const char* fluorescence, const char* light) {
    RenderSettings r = scene->render;
    r.wavelengths.sensor = parseWavelengthSpec(sensor);
    r.wavelengths.fluorescence = parseWavelengthSpec(fluorescence);
    r.wavelengths.light = parseWavelengthSpec(light);
    return r;
  };
  EXPECT_NO_THROW(makeIntegrator("pt", *scene, with("ms-power:cmf,light", "mix:absorption,light", "light")));
  expectStrategyError([&] { makeIntegrator("pt", *scene, with("cmf", "material", "uniform")); },
                      WavelengthSite::LightStart, "does not apply to the integrator pt");
  expectStrategyError([&] { makeIntegrator("lt", *scene, with("uniform", "material", "light")); },
                      WavelengthSite::Sensor, "does not apply to the integrator lt");
  expectStrategyError([&] { makeIntegrator("bdpt", *scene, with("cmf", "uniform", "light")); },
                      WavelengthSite::Fluorescence, "does not apply to the integrator bdpt");
  expectStrategyError([&] { makeIntegrator("bdpt-shared", *scene, with("cmf", "material", "uniform")); },
                      WavelengthSite::LightStart, "does not apply to the integrator bdpt with families \"shared\"");
  expectStrategyError([&] { makeIntegrator("bdpt", *scene, with("ms-balance:cmf,uniform", "material", "light")); },
                      WavelengthSite::Sensor, "needs one density");
  expectStrategyError([&] { makeIntegrator("ppm", *scene, with("cmf", "material", "os-power:light,uniform")); },
                      WavelengthSite::LightStart, "needs one density");
  // Hero wavelengths: a sensor density for the strata.
  RenderSettings hero = with("cmf", "material", "light");
  hero.heroWavelengths = 4;
  EXPECT_NO_THROW(makeIntegrator("pt", *scene, hero));
  EXPECT_NO_THROW(makeIntegrator("bdpt", *scene, hero));
  hero.wavelengths.sensor = parseWavelengthSpec("ms-balance:cmf,light");
  expectStrategyError([&] { makeIntegrator("pt", *scene, hero); }, WavelengthSite::Sensor, "needs one density");
  // Next-event estimation's own excitation wavelength: the path tracer only, not with hero wavelengths.
  RenderSettings nee = with("cmf", "material", "light");
  nee.wavelengths.nee = parseWavelengthSpec("mix:absorption,light");
  EXPECT_NO_THROW(makeIntegrator("pt", *scene, nee));
  expectStrategyError([&] { makeIntegrator("bdpt", *scene, nee); }, WavelengthSite::Nee,
                      "does not apply to the integrator bdpt");
  nee.heroWavelengths = 4;
  expectStrategyError([&] { makeIntegrator("pt", *scene, nee); }, WavelengthSite::Nee, "not supported with hero");
  nee.heroWavelengths = 1;
  nee.wavelengths.nee = parseWavelengthSpec("material");
  expectStrategyError([&] { makeIntegrator("pt", *scene, nee); }, WavelengthSite::Nee, "applies only to");
  nee.wavelengths.nee = parseWavelengthSpec("event");
  nee.wavelengths.fluorescence = parseWavelengthSpec("event");
  expectStrategyError([&] { makeIntegrator("pt", *scene, nee); }, WavelengthSite::Fluorescence, "applies only to");
}

// Every fluorescent material says what it absorbs and re-emits (here measured Post-it matrices
// and their Zhdanov fits under UV): strategies that follow fluorophores serve all of them, and a
// sensor density that only follows the light is still refused, as it would render the visible
// fluorescence black.
TEST(WavelengthStrategy, EveryFluorescentMaterialGivesItsFluorophore) {
  const auto scene = loadScene(KASHA_SOURCE_DIR "/scenes/postit_uv.json");
  const WavelengthSources src(*scene);
  size_t fluorescent = 0;
  for (const auto& m : scene->materials) fluorescent += has(m->flags(), BsdfFlags::Fluorescent) ? 1 : 0;
  ASSERT_GE(fluorescent, 4u);
  EXPECT_EQ(src.fluorophores.size(), fluorescent);
  for (const WavelengthSources::Fluorophore& f : src.fluorophores) {
    EXPECT_GT(f.spectra.absorbed.integral(src.range), 0.0f) << scene->materialNames[f.material];
    EXPECT_GT(f.spectra.reemitted.integral(src.range), 0.0f) << scene->materialNames[f.material];
  }
  expectStrategyError([&] { build("light", src, WavelengthSite::Sensor); }, WavelengthSite::Sensor,
                      "has density 0 at");
  EXPECT_NO_THROW(build("mix:light,cmf", src, WavelengthSite::Sensor));
  for (const char* spec : {"absorption", "yamamoto", "material", "mix:absorption,uniform"})
    EXPECT_NO_THROW(FluorescenceSampling(parseWavelengthSpec(spec), src, scene->materials.size())) << spec;
  // Refused only where biased, naming the strategy asked for: the emission misses the excitation.
  expectStrategyError(
      [&] { FluorescenceSampling(parseWavelengthSpec("emission"), src, scene->materials.size()); },
      WavelengthSite::Fluorescence, "wavelength strategy 'emission' at the fluorescence site has density 0");
}

}  // namespace
}  // namespace kasha
