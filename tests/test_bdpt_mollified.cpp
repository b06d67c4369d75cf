// BDPT with spectral mollification (integrator "bdpt-mollified", docs/bdpt-mis.md §6): the
// bandwidth schedule, convergence to the white furnace's closed form (validation.md §1 with
// c = 0) within k·SE plus a bias bound derived below, and that the mollified strategies carry a
// real share of the image where the exact Independent family has no s ≥ 2 connection at all.
#include <gtest/gtest.h>

#include <cmath>

#include "core/color.h"
#include "core/scene_loader.h"
#include "integrators/bdpt/bdpt_integrator.h"
#include "integrators/bdpt/strategy_images.h"
#include "integrators/integrator_factory.h"
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
  MollificationSettings m;
  m.bandwidth = 12.0f;
  m.alpha = 0.5f;
  const Bdpt bdpt(*scene, SensorSampling::Uniform, bdpt::WalkSettings{}, &m);
  EXPECT_TRUE(bdpt.mollifies());
  EXPECT_EQ(bdpt.name(), "bdpt-mollified");
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
  MollificationSettings bad = m;
  bad.alpha = 1.0f;
  EXPECT_THROW(Bdpt(*scene, SensorSampling::Uniform, bdpt::WalkSettings{}, &bad), std::invalid_argument);
  EXPECT_THROW(Bdpt(*scene, SensorSampling::Uniform, bdpt::WalkSettings{64, 3, bdpt::WavelengthMode::Shared}, &m),
               std::invalid_argument);
}

struct Batches {
  test::BatchStats xyz[3];
  double mollifiedShareY = 0.0;  // the mollified strategies' share of the image's Y
  bool connections = false;      // some strategy with s ≥ 2, t ≥ 2 contributed
};

// Renders the scene in independent batches, with every strategy's share recorded.
Batches renderBatches(Scene& scene, const std::string& integrator, int maxDepth, int batches, int spp) {
  RenderSettings s = scene.render;
  s.maxDepth = maxDepth;
  s.rrDepth = 3;
  s.sensor = SensorSampling::Uniform;
  s.mollify.bandwidth = 20.0f;
  const auto bdpt = makeIntegrator(integrator, scene, s);
  std::vector<double> b[3];
  double mollified = 0.0, total = 0.0;
  Batches run;
  for (int i = 0; i < batches; ++i) {
    Film film(scene.camera.width(), scene.camera.height());
    bdpt::StrategyImages images(film.width(), film.height(), 64);
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
// density and MIS weight is the same at every wavelength, so a mollified connection's expected
// value equals the exact one except where the kernel K_h(λ_L − λ_C) reaches past the ends of the
// wavelength range and loses mass 1 − ∫K_h dλ_L ≤ 1, i.e. for λ_C within h_1 of either end. The
// mollified strategies' weighted share at λ_C is at most the whole radiance L there, so
//   |bias| ≤ L · ∫_{ends within h_1} (x̄, ȳ, z̄) dλ / ∫ȳ dλ,
// largest for the first pass (h_i decreases).
void expectWhiteFurnace(int maxDepth, int batches, int spp) {
  auto scene = load("furnace_white.json");
  const auto& m = dynamic_cast<const JungBbrrdf&>(*scene->materials.at(0));
  ASSERT_EQ(m.c(), 0.0f);
  const double r = m.r(500.0f), Le = scene->shapes.at(0).emission->scale * scene->shapes.at(0).emission->radiance(500.0f);
  double L = 0.0;  // Σ_{j ≤ d} r^j L_e (the Neumann series, validation.md §1)
  for (int j = 0; j <= std::min(maxDepth, 2000); ++j) L += std::pow(r, j) * Le;
  const float h1 = 20.0f;
  const WavelengthRange range = scene->range;
  const Vec3 exact = cmfIntegral(range.min, range.max) * float(L);
  const Vec3 bias = (cmfIntegral(range.min, range.min + h1) + cmfIntegral(range.max - h1, range.max)) * float(L);
  const Batches run = renderBatches(*scene, "bdpt-mollified", maxDepth, batches, spp);
  for (int c = 0; c < 3; ++c) {
    SCOPED_TRACE("channel " + std::string(1, "XYZ"[c]) + " depth " + std::to_string(maxDepth));
    EXPECT_LT(run.xyz[c].stderr_, 0.03 * exact[c]);  // the test has power
    EXPECT_NEAR(run.xyz[c].mean, exact[c], 4.0 * run.xyz[c].stderr_ + bias[c])
        << "mean " << run.xyz[c].mean << " ± " << run.xyz[c].stderr_ << ", bias bound " << bias[c];
  }
  // Paths with two scattering vertices or more have mollified strategies, with non-zero weights.
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
  // independently chosen wavelengths. Constant spectra and uniform sensor sampling: the bias is
  // bounded as in the white furnace, by the colour matching functions' share within h_1 of the ends.
  auto scene = load("mollify_mirror.json");
  const Batches exact = renderBatches(*scene, "bdpt-independent", 8, 1, 16);
  EXPECT_FALSE(exact.connections);
  for (int c = 0; c < 3; ++c) EXPECT_EQ(exact.xyz[c].mean, 0.0);
  const Batches shared = renderBatches(*scene, "bdpt-shared", 8, 16, 128);
  const Batches moll = renderBatches(*scene, "bdpt-mollified", 8, 16, 128);
  EXPECT_TRUE(moll.connections);
  EXPECT_NEAR(moll.mollifiedShareY, 1.0, 1e-4) << "all the light comes through mollified connections";
  const WavelengthRange r = scene->range;
  const Vec3 all = cmfIntegral(r.min, r.max), ends = cmfIntegral(r.min, r.min + 20.0f) + cmfIntegral(r.max - 20.0f, r.max);
  for (int c = 0; c < 3; ++c) {
    SCOPED_TRACE("channel " + std::string(1, "XYZ"[c]));
    EXPECT_LT(moll.xyz[c].stderr_, 0.1 * moll.xyz[c].mean);  // the test has power (a kernel off by 20% would show)
    const double se = std::hypot(shared.xyz[c].stderr_, moll.xyz[c].stderr_);
    const double bias = (moll.xyz[c].mean + 4.0 * moll.xyz[c].stderr_) * ends[c] / all[c];
    EXPECT_NEAR(moll.xyz[c].mean, shared.xyz[c].mean, 4.0 * se + bias)
        << "mollified " << moll.xyz[c].mean << " ± " << moll.xyz[c].stderr_ << ", shared " << shared.xyz[c].mean
        << " ± " << shared.xyz[c].stderr_ << ", bias bound " << bias;
  }
}

}  // namespace
}  // namespace kasha
