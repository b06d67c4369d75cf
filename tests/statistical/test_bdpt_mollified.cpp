// BDPT with spectral mollification (integrator "bdpt-mollified", docs/bdpt-mis.md §6): the
// bandwidth schedule and the range-renormalised kernel, convergence to the white furnace's
// closed form (docs/validation.md §1 with c = 0) within 4σ (the bias bound derived below is zero),
// and a scene the exact Independent family cannot render at all, where it agrees with Shared.
#include <gtest/gtest.h>

#include <cmath>

#include "core/color.h"
#include "scene/scene_loader.h"
#include "integrators/bidirectional/bdpt.h"
#include "integrators/bidirectional/strategy_images.h"
#include "integrators/integrator_factory.h"
#include "integrators/progressive_schedule.h"
#include "integrators/render_loop.h"
#include "materials/jung_bbrrdf.h"
#include "tests/support.h"

namespace kasha {
namespace {

std::unique_ptr<Scene> load(const std::string& name) { return loadScene(test::sourcePath("scenes/validation/" + name)); }

// ∫ x̄, ȳ, z̄ dλ over [lo, hi] in the film's normalisation (divided by ∫ȳ), midpoint rule on 0.05 nm.
Vec3 cmfIntegral(float lo, float hi) {
  const Observer& o = Observer::cie1931();
  const double step = 0.05;
  double X = 0, Y = 0, Z = 0;
  for (double l = lo + 0.5 * step; l < hi; l += step) {
    X += o.xbar(float(l)) * step, Y += o.ybar(float(l)) * step, Z += o.zbar(float(l)) * step;
  }
  return Vec3(float(X / o.yIntegral), float(Y / o.yIntegral), float(Z / o.yIntegral));
}

TEST(BdptMollified, BandwidthShrinksLikeThePhotonMappingRadius) {
  auto scene = load("furnace_white.json");
  RenderSettings rs = scene->render;
  rs.wavelengths.sensor = parseWavelengthSpec("uniform");
  rs.bdpt.families = BdptFamilies::Own;
  rs.bdpt.mollify = true;
  rs.bdpt.mollifyBandwidth = 12.0f;
  rs.bdpt.mollifyAlpha = 0.5f;
  const Bdpt bdpt(*scene, rs);
  EXPECT_TRUE(bdpt.mollifies());
  EXPECT_EQ(bdpt.maxSamplesPerPass(), 1);  // one iteration per sample index
  double h2 = 144.0;
  for (int i = 1; i <= 2000; ++i) {
    if (i > 1) h2 *= (i - 1 + 0.5) / i;  // Knaus & Zwicker 2011 eq. 15, in wavelength
    ASSERT_NEAR(bdpt.bandwidth(i - 1), std::sqrt(h2), 1e-5 * std::sqrt(h2)) << "iteration " << i;
  }
  EXPECT_LT(bdpt.bandwidth(1999), 0.2f * 12.0f);  // h_i ~ i^{(α−1)/2}/√Γ(1 + α) → 0
  // The default h_1 is 2% of the wavelength range; bdpt-independent does not mollify.
  const auto byName = makeIntegrator("bdpt-mollified", *scene, scene->render);
  EXPECT_NEAR(static_cast<const Bdpt&>(*byName).bandwidth(0), 0.02f * (scene->range.max - scene->range.min), 1e-4f);
  EXPECT_FALSE(static_cast<const Bdpt&>(*makeIntegrator("bdpt-independent", *scene, scene->render)).mollifies());
  // The kernel's mass inside a range: the whole kernel, half at an end, none outside.
  EXPECT_NEAR(wavelengthKernelMass(-30.0f, 30.0f, 12.0f), 1.0f, 1e-6f);
  EXPECT_NEAR(wavelengthKernelMass(0.0f, 30.0f, 12.0f), 0.5f, 1e-6f);
  EXPECT_EQ(wavelengthKernelMass(13.0f, 30.0f, 12.0f), 0.0f);
  double mass = 0.0;
  for (double x = -5.0 + 0.0005; x < 7.0; x += 0.001) mass += wavelengthKernel(float(x), 12.0f) * 0.001;
  EXPECT_NEAR(wavelengthKernelMass(-5.0f, 7.0f, 12.0f), mass, 1e-5);
  RenderSettings bad = rs;
  bad.bdpt.mollifyAlpha = 1.0f;
  EXPECT_THROW(Bdpt(*scene, bad), std::invalid_argument);
  bad = rs;
  bad.bdpt.families = BdptFamilies::Shared;  // mollification is of the own family's connections
  EXPECT_THROW(Bdpt(*scene, bad), std::invalid_argument);
}

struct Batches {
  test::BatchStats xyz[3];
  double mollifiedShareY = 0.0;  // the mollified strategies' share of the image's Y
  bool connections = false;      // some strategy with s ≥ 2, t ≥ 2 contributed
};

// Renders the scene in independent batches, with every strategy's share recorded.
Batches renderBatches(Scene& scene, const std::string& integrator, int maxDepth, int batches, int spp,
                      float bandwidth = 20.0f) {
  RenderSettings s = scene.render;
  s.maxDepth = maxDepth;
  s.rrDepth = 3;
  s.wavelengths.sensor = parseWavelengthSpec("uniform");
  s.bdpt.mollifyBandwidth = bandwidth;
  const auto bdpt = makeIntegrator(integrator, scene, s);
  std::vector<double> b[3];
  double mollified = 0.0, total = 0.0;
  Batches run;
  for (int i = 0; i < batches; ++i) {
    Film film(scene.camera.width(), scene.camera.height());
    bidir::StrategyImages images(film.width(), film.height(), 64, scene.pixelFilter);
    RenderOptions opt;
    opt.spp = spp;
    opt.seed = 500 + uint64_t(i);
    opt.strategies = [&](const StrategySample& r) {
      images.add(r);
      if (r.s >= 2 && r.t >= 2) run.connections = true;
    };
    render(scene, *bdpt, film, opt);
    images.setSamplesPerPixel(spp);
    for (const auto& [name, img] : images.images())
      if (name.find("_mollified") != std::string::npos) mollified += img->weighted.meanXyz().y;
    const DVec3 m = film.meanXyz();
    total += m.y;
    b[0].push_back(m.x), b[1].push_back(m.y), b[2].push_back(m.z);
  }
  for (int c = 0; c < 3; ++c) run.xyz[c] = test::batchStats(b[c]);
  run.mollifiedShareY = mollified / total;
  return run;
}

// White furnace (c = 0, r and L_e constant, uniform sensor sampling): every spectral quantity,
// density and MIS weight is the same at every wavelength, and the kernel is renormalised to its
// mass inside the wavelength range, so a mollified connection's expectation equals the exact
// one for any h (docs/bdpt-mis.md eq. 7): the bias bound is zero and the test is 4σ. A wide
// kernel (h_1 = 150 nm) gives the mollified strategies as much weight as they can get here.
void expectWhiteFurnace(int maxDepth, int batches, int spp) {
  auto scene = load("furnace_white.json");
  const auto& m = dynamic_cast<const JungBbrrdf&>(*scene->materials.at(0));
  ASSERT_EQ(m.c(), 0.0f);
  const double r = m.r(500.0f), Le = scene->shapes.at(0).emission->scale * scene->shapes.at(0).emission->radiance(500.0f);
  double L = 0.0;  // Σ_{j ≤ d} r^j L_e (the Neumann series, docs/validation.md §1)
  for (int j = 0; j <= std::min(maxDepth, 2000); ++j) L += std::pow(r, j) * Le;
  const Vec3 exact = cmfIntegral(scene->range.min, scene->range.max) * float(L);
  const Batches run = renderBatches(*scene, "bdpt-mollified", maxDepth, batches, spp, 150.0f);
  for (int c = 0; c < 3; ++c) {
    SCOPED_TRACE("channel " + std::string(1, "XYZ"[c]) + " depth " + std::to_string(maxDepth));
    EXPECT_LT(run.xyz[c].stderr_, 0.03 * exact[c]);  // the test has power
    EXPECT_NEAR(run.xyz[c].mean, exact[c], 4.0 * run.xyz[c].stderr_)
        << "mean " << run.xyz[c].mean << " ± " << run.xyz[c].stderr_;
  }
  // Paths with two scattering vertices or more have mollified strategies. Their weighted share
  // stays near 1% here: next-event estimation and the camera path hitting the emitting walls are
  // far better strategies in a furnace, and a mollified connection's density carries the factor
  // ε_h·p(λ) ≤ 4h/(3·470 nm) (docs/bdpt-mis.md eq. 6).
  EXPECT_EQ(run.connections, maxDepth >= 2);
  EXPECT_EQ(run.mollifiedShareY > 0.0, maxDepth >= 2);
}

TEST(BdptMollified, WhiteFurnaceAllOrders) { expectWhiteFurnace(1000, 16, 128); }

TEST(BdptMollified, WhiteFurnaceEachPathLength) {
  for (int d = 2; d <= 3; ++d) {
    expectWhiteFurnace(d, 8, 128);
  }
}

TEST(BdptMollified, MollifiedConnectionsRenderWhatTheExactIndependentFamilyCannot) {
  // A point light inside a glass sphere lights a room the camera sees only in a mirror: both
  // subpaths start with specular vertices, the light is a delta and nothing fluoresces, so the
  // exact Independent family has no strategy for any path (its image is black). The Shared family
  // joins the floor and the back wall exactly; mollified connections join them across
  // independently chosen wavelengths. Constant spectra and uniform sensor sampling: no bias, as in
  // the white furnace.
  auto scene = load("mollify_mirror.json");
  const Batches exact = renderBatches(*scene, "bdpt-independent", 8, 1, 16);
  EXPECT_FALSE(exact.connections);
  for (int c = 0; c < 3; ++c) EXPECT_EQ(exact.xyz[c].mean, 0.0);
  const Batches shared = renderBatches(*scene, "bdpt-shared", 8, 16, 256);
  const Batches moll = renderBatches(*scene, "bdpt-mollified", 8, 16, 256, 150.0f);
  EXPECT_TRUE(moll.connections);
  EXPECT_NEAR(moll.mollifiedShareY, 1.0, 1e-4) << "all the light comes through mollified connections";
  for (int c = 0; c < 3; ++c) {
    SCOPED_TRACE("channel " + std::string(1, "XYZ"[c]));
    // The test has power: with both errors below 6% a 25% error in the mollified estimate shows.
    EXPECT_LT(moll.xyz[c].stderr_, 0.06 * moll.xyz[c].mean);
    EXPECT_LT(shared.xyz[c].stderr_, 0.06 * shared.xyz[c].mean);
    const double se = std::hypot(shared.xyz[c].stderr_, moll.xyz[c].stderr_);
    EXPECT_NEAR(moll.xyz[c].mean, shared.xyz[c].mean, 4.0 * se)
        << "mollified " << moll.xyz[c].mean << " ± " << moll.xyz[c].stderr_ << ", shared " << shared.xyz[c].mean
        << " ± " << shared.xyz[c].stderr_;
  }
}

}  // namespace
}  // namespace kasha
