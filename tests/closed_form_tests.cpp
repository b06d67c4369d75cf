// Every integrator against the closed forms of validation.md §1–2, with tolerances of 4 standard
// errors estimated from independent batches. Expected values are computed here by quadrature of
// the formulas from the very spectra the scene files load. This file is compiled once per
// integrator (tests/CMakeLists.txt), with KASHA_TEST_INTEGRATOR naming it.
#include <gtest/gtest.h>

#include <functional>

#include "core/color.h"
#include "core/scene_loader.h"
#include "integrators/integrator_factory.h"
#include "integrators/render_loop.h"
#include "materials/jung_bbrrdf.h"
#include "tests/support.h"

namespace kasha {
namespace {

using Fn = std::function<double(double)>;

// Midpoint quadrature on a 0.05 nm grid aligned with whole nanometres, so steps of the box spectra
// and knots of the 1 nm CIE tables fall on cell boundaries.
constexpr double kStep = 0.05;

struct Grid {
  std::vector<double> x;
  explicit Grid(WavelengthRange r) {
    for (double l = r.min + 0.5 * kStep; l < r.max; l += kStep) x.push_back(l);
  }
  double integrate(const std::vector<double>& f) const {
    double s = 0.0;
    for (double v : f) s += v * kStep;
    return s;
  }
  std::vector<double> sample(const Fn& f) const {
    std::vector<double> v(x.size());
    for (size_t i = 0; i < x.size(); ++i) v[i] = f(x[i]);
    return v;
  }
};

// XYZ of a radiance spectrum given on the grid, in the film's normalisation.
Vec3 toXyz(const Grid& g, const std::vector<double>& L) {
  const Observer& o = Observer::cie1931();
  double X = 0, Y = 0, Z = 0;
  for (size_t i = 0; i < g.x.size(); ++i) {
    X += o.xbar(float(g.x[i])) * L[i] * kStep;
    Y += o.ybar(float(g.x[i])) * L[i] * kStep;
    Z += o.zbar(float(g.x[i])) * L[i] * kStep;
  }
  return Vec3(float(X / o.yIntegral), float(Y / o.yIntegral), float(Z / o.yIntegral));
}

const JungBbrrdf& jung(const Scene& s) {
  const auto* m = dynamic_cast<const JungBbrrdf*>(s.materials.at(0).get());
  EXPECT_NE(m, nullptr);
  return *m;
}

// Applies the furnace transport operator once to a uniform isotropic radiance L (Jung18 eq. 4
// integrated over the hemisphere): (T L)(λ) = (1 − c·a)·r·L(λ) + Q·e(λ)·∫ c·a·L dλ.
std::vector<double> transport(const Grid& g, const JungBbrrdf& m, const std::vector<double>& L) {
  std::vector<double> ca = g.sample([&](double l) { return m.c() * m.a(float(l)); });
  std::vector<double> absorbed(g.x.size());
  for (size_t i = 0; i < L.size(); ++i) absorbed[i] = ca[i] * L[i];
  const double A = g.integrate(absorbed);
  std::vector<double> out(L.size());
  for (size_t i = 0; i < L.size(); ++i)
    out[i] = (1.0 - ca[i]) * m.r(float(g.x[i])) * L[i] + m.q() * m.e(float(g.x[i])) * A;
  return out;
}

// validation.md §1: L = [L_e + Q·e·K] / D, D = 1 − (1 − c·a)·r, K = A / (1 − Q·B).
std::vector<double> furnaceClosedForm(const Grid& g, const JungBbrrdf& m, const Fn& Le) {
  std::vector<double> D = g.sample([&](double l) { return 1.0 - (1.0 - m.c() * m.a(float(l))) * m.r(float(l)); });
  std::vector<double> fa(g.x.size()), fb(g.x.size());
  for (size_t i = 0; i < g.x.size(); ++i) {
    const double ca = m.c() * m.a(float(g.x[i]));
    fa[i] = ca * Le(g.x[i]) / D[i];
    fb[i] = ca * m.e(float(g.x[i])) / D[i];
  }
  const double K = g.integrate(fa) / (1.0 - m.q() * g.integrate(fb));
  std::vector<double> L(g.x.size());
  for (size_t i = 0; i < g.x.size(); ++i) L[i] = (Le(g.x[i]) + m.q() * m.e(float(g.x[i])) * K) / D[i];
  return L;
}

const std::string gIntegrator = KASHA_TEST_INTEGRATOR;
// Light tracing spends most paths where the small test cameras do not look, and so does photon
// mapping (its photons land everywhere, and the test images hold only 64 pixels, so 64 photons a
// pass): they get more samples so that every test keeps its power (the standard-error check
// below). Photon mapping's kernels add no bias here (docs/photon-mapping.md, "Validation").
const int gSppScale = gIntegrator == "lt" ? 8 : gIntegrator == "ppm" ? 2 : 1;

// Mean image XYZ over `batches` independent renders; checks each channel within 4σ.
void expectAgreement(Scene& scene, int maxDepth, const Vec3& exact, int batches = 16, int spp = 256,
                     SensorSampling sensor = SensorSampling::ColorMatching) {
  RenderSettings settings = scene.render;
  settings.maxDepth = maxDepth;
  settings.rrDepth = 3;
  settings.sensor = sensor;
  const std::unique_ptr<Integrator> integrator = makeIntegrator(gIntegrator, scene, settings);
  std::vector<double> bx, by, bz;
  for (int b = 0; b < batches; ++b) {
    Film film(scene.camera.width(), scene.camera.height());
    RenderOptions opt;
    opt.spp = spp * gSppScale;
    opt.seed = 1000 + uint64_t(b);
    render(scene, *integrator, film, opt);
    const DVec3 m = film.meanXyz();
    bx.push_back(m.x), by.push_back(m.y), bz.push_back(m.z);
  }
  const test::BatchStats s[3] = {test::batchStats(bx), test::batchStats(by), test::batchStats(bz)};
  for (int c = 0; c < 3; ++c) {
    SCOPED_TRACE("channel " + std::string(1, "XYZ"[c]) + " depth " + std::to_string(maxDepth));
    // The test must have power: the standard error is small against the value (or, for values
    // near zero such as the direct view of a UV emitter, small in absolute terms: scenes are O(1)).
    EXPECT_LT(s[c].stderr_, 0.03 * std::abs(exact[c]) + 1e-4);
    EXPECT_NEAR(s[c].mean, exact[c], 4.0 * s[c].stderr_ + 1e-5 * std::abs(exact[c]))
        << "mean " << s[c].mean << " ± " << s[c].stderr_ << ", exact " << exact[c];
  }
}

std::unique_ptr<Scene> load(const std::string& name) { return loadScene(test::sourcePath("scenes/validation/" + name)); }

Fn emissionOf(const Scene& s) {
  const AreaEmission& e = *s.shapes.at(0).emission;
  return [e](double l) { return double(e.scale * e.radiance(float(l))); };
}

TEST(ClosedForm, WorkedExampleMatchesValidationDoc) {
  // validation.md §1 quotes L = 1.111 / 2.000 / 3.600 in the absorption / neutral / emission bands.
  auto scene = load("furnace_fluorescent.json");
  const Grid g(scene->range);
  const std::vector<double> L = furnaceClosedForm(g, jung(*scene), emissionOf(*scene));
  auto at = [&](double l) { return L[size_t((l - scene->range.min) / kStep)]; };
  EXPECT_NEAR(at(425.0), 1.111, 1e-3);
  EXPECT_NEAR(at(500.0), 2.000, 1e-3);
  EXPECT_NEAR(at(575.0), 3.600, 1e-3);
}

TEST(ClosedForm, NeumannSeriesConvergesToClosedForm) {
  for (const char* name : {"furnace_fluorescent.json", "furnace_overlap.json", "furnace_uv.json"}) {
    auto scene = load(name);
    const Grid g(scene->range);
    const JungBbrrdf& m = jung(*scene);
    std::vector<double> term = g.sample(emissionOf(*scene)), sum = term;
    for (int k = 0; k < 300; ++k) {
      term = transport(g, m, term);
      for (size_t i = 0; i < sum.size(); ++i) sum[i] += term[i];
    }
    const std::vector<double> closed = furnaceClosedForm(g, m, emissionOf(*scene));
    for (size_t i = 0; i < sum.size(); i += 97) EXPECT_NEAR(sum[i], closed[i], 1e-6 * (1.0 + closed[i])) << name;
  }
}

class Furnace : public ::testing::TestWithParam<const char*> {};

TEST_P(Furnace, AllOrders) {
  auto scene = load(GetParam());
  const Grid g(scene->range);
  const Vec3 exact = toXyz(g, furnaceClosedForm(g, jung(*scene), emissionOf(*scene)));
  expectAgreement(*scene, 1000, exact);
}

TEST_P(Furnace, EachPathLength) {
  // A depth limit d keeps the Neumann series up to d bounces: each length is checked on its own.
  auto scene = load(GetParam());
  const Grid g(scene->range);
  std::vector<double> term = g.sample(emissionOf(*scene)), sum = term;
  for (int d = 0; d <= 3; ++d) {
    if (d > 0) {
      term = transport(g, jung(*scene), term);
      for (size_t i = 0; i < sum.size(); ++i) sum[i] += term[i];
    }
    expectAgreement(*scene, d, toXyz(g, sum), 8, 256);
  }
}

INSTANTIATE_TEST_SUITE_P(Scenes, Furnace,
                         ::testing::Values("furnace_white.json", "furnace_fluorescent.json", "furnace_overlap.json",
                                           "furnace_uv.json"));

TEST(ClosedForm, WhiteFurnaceIsLeOverOneMinusR) {
  auto scene = load("furnace_white.json");
  const Grid g(scene->range);
  // c = 0: the ordinary white furnace L = L_e / (1 − r), independently of the fluorescent formula.
  const JungBbrrdf& m = jung(*scene);
  ASSERT_EQ(m.c(), 0.0f);
  const Vec3 exact = toXyz(g, g.sample([&](double l) { return 1.0 / (1.0 - m.r(float(l))); }));
  expectAgreement(*scene, 1000, exact, 8, 256);
}

TEST(ClosedForm, UniformSensorSamplingAgrees) {
  auto scene = load("furnace_overlap.json");
  const Grid g(scene->range);
  const Vec3 exact = toXyz(g, furnaceClosedForm(g, jung(*scene), emissionOf(*scene)));
  expectAgreement(*scene, 1000, exact, 16, 256, SensorSampling::Uniform);
}

TEST(ClosedForm, PointLightInsideFluorescentSphere) {
  // Direct irradiance E = I/R² is uniform over the sphere, so every later bounce stays uniform:
  // L = Σ_k T^k L_1, i.e. the furnace closed form with L_1 in place of L_e.
  auto scene = load("furnace_point_light.json");
  const JungBbrrdf& m = jung(*scene);
  const auto& light = dynamic_cast<const PointLight&>(*scene->lights.at(0));
  const float R = scene->shapes.at(0).radius;
  const Grid g(scene->range);
  const Fn E = [&](double l) { return light.intensity(float(l)) / (R * R); };
  const double absorbed = g.integrate(g.sample([&](double l) { return m.c() * m.a(float(l)) * E(l); }));
  const Fn L1 = [&](double l) {
    const float lf = float(l);
    return ((1.0 - m.c() * m.a(lf)) * m.r(lf) * E(l) + m.q() * m.e(lf) * absorbed) / kPi;
  };
  expectAgreement(*scene, 1000, toXyz(g, furnaceClosedForm(g, m, L1)));
}

// validation.md §2, uniform environment: L_o = (1 − c·a)·r·L_i + Q·e·∫ c·a·L_i dλ.
TEST(ClosedForm, SingleScatteringSphereUnderEnvironment) {
  auto scene = load("single_sphere_environment.json");
  const JungBbrrdf& m = jung(*scene);
  const EnvironmentLight& env = *scene->environment();
  const Grid g(scene->range);
  const double absorbed = g.integrate(g.sample([&](double l) { return m.c() * m.a(float(l)) * env.Le(float(l)); }));
  const std::vector<double> L = g.sample([&](double l) {
    const float lf = float(l);
    return (1.0 - m.c() * m.a(lf)) * m.r(lf) * env.Le(lf) + m.q() * m.e(lf) * absorbed;
  });
  // The worked example: 0.10 / 0.50 / 1.22 in the three bands.
  EXPECT_NEAR(L[size_t((425.0 - scene->range.min) / kStep)], 0.10, 1e-3);
  EXPECT_NEAR(L[size_t((575.0 - scene->range.min) / kStep)], 1.22, 1e-3);
  expectAgreement(*scene, 1000, toXyz(g, L), 16, 512);
}

// validation.md §2, distant light: L_o = cos θ·[(1 − c·a)·r·E + Q·e·∫ c·a·E dλ] / π.
void checkPlane(const std::string& name) {
  auto scene = load(name);
  const JungBbrrdf& m = jung(*scene);
  const auto& light = dynamic_cast<const DistantLight&>(*scene->lights.at(0));
  const float cosTheta = std::abs(light.direction().y);
  const Grid g(scene->range);
  const double absorbed = g.integrate(g.sample([&](double l) { return m.c() * m.a(float(l)) * light.irradiance(float(l)); }));
  const std::vector<double> L = g.sample([&](double l) {
    const float lf = float(l);
    return cosTheta * ((1.0 - m.c() * m.a(lf)) * m.r(lf) * light.irradiance(lf) + m.q() * m.e(lf) * absorbed) / kPi;
  });
  expectAgreement(*scene, 1000, toXyz(g, L));
}

TEST(ClosedForm, SingleScatteringPlaneUnderDistantLight) { checkPlane("single_plane_distant.json"); }
TEST(ClosedForm, SingleScatteringPlaneUnderUvLightIsPurelyFluorescent) { checkPlane("single_plane_uv.json"); }

}  // namespace
}  // namespace kasha
