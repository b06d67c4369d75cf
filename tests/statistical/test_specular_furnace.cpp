// Closed-form furnaces with specular materials (scenes/validation/furnace_mirror.json and
// furnace_glass*.json), rendered with the integrators that can produce their paths. Tolerances
// are 4 standard errors estimated from independent batches; expected values are quadratures of
// the formulas over the spectra and indices the scene files load.
//
// Which integrator renders what: the path tracer follows specular chains from the camera. The
// light tracer connects only non-specular vertices to the camera, so it cannot see a mirror or
// glass at all, directly or through other specular surfaces (only bidirectional methods with
// specular handling would); it is tested on the scene whose camera sees only diffuse walls.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <functional>
#include <string>

#include "core/color.h"
#include "scene/scene_loader.h"
#include "integrators/integrator_factory.h"
#include "integrators/render_loop.h"
#include "materials/dielectric.h"
#include "materials/lambertian.h"
#include "materials/mirror.h"
#include "tests/process.h"
#include "tests/support.h"

namespace kasha {
namespace {

using Fn = std::function<double(double)>;

// XYZ of a radiance spectrum in the film's normalisation, by the midpoint rule on a 0.05 nm grid
// aligned with whole nanometres (the knots of the 1 nm CIE tables fall on cell boundaries).
Vec3 toXyz(WavelengthRange range, const Fn& L) {
  constexpr double kStep = 0.05;
  const Observer& o = Observer::cie1931();
  double X = 0, Y = 0, Z = 0;
  for (double l = range.min + 0.5 * kStep; l < range.max; l += kStep) {
    const double v = L(l) * kStep;
    X += o.xbar(float(l)) * v;
    Y += o.ybar(float(l)) * v;
    Z += o.zbar(float(l)) * v;
  }
  return Vec3(float(X / o.yIntegral), float(Y / o.yIntegral), float(Z / o.yIntegral));
}

std::unique_ptr<Scene> load(const std::string& name) { return loadScene(test::sourcePath("scenes/validation/" + name)); }

template <class M>
const M& material(const Scene& s, const std::string& name) {
  for (size_t i = 0; i < s.materialNames.size(); ++i)
    if (s.materialNames[i] == name) {
      const auto* m = dynamic_cast<const M*>(s.materials[i].get());
      if (m) return *m;
    }
  throw std::runtime_error("scene has no material '" + name + "' of the expected type");
}

// Emitted radiance of shape i.
Fn emission(const Scene& s, size_t i) {
  const AreaEmission& e = *s.shapes.at(i).emission;
  return [e](double l) { return double(e.scale * e.radiance(float(l))); };
}

// Mean image XYZ over `batches` independent renders; checks each channel within 4σ and that the
// test has power (σ small against the value).
void expectAgreement(const Scene& scene, const std::string& integratorName, int maxDepth, const Vec3& exact,
                     int batches, int spp) {
  SCOPED_TRACE(integratorName + ", depth " + std::to_string(maxDepth));
  RenderSettings settings = scene.render;
  settings.maxDepth = maxDepth;
  settings.rrDepth = 3;
  const std::unique_ptr<Integrator> integrator = makeIntegrator(integratorName, scene, settings);
  std::vector<double> b[3];
  for (int k = 0; k < batches; ++k) {
    Film film(scene.camera.width(), scene.camera.height());
    RenderOptions opt;
    opt.spp = spp;
    opt.seed = 2000 + uint64_t(k);
    render(scene, *integrator, film, opt);
    EXPECT_EQ(film.nonFiniteCount(), 0u);
    const DVec3 m = film.meanXyz();
    b[0].push_back(m.x), b[1].push_back(m.y), b[2].push_back(m.z);
  }
  for (int c = 0; c < 3; ++c) {
    const test::BatchStats s = test::batchStats(b[c]);
    EXPECT_LT(s.stderr_, 0.02 * exact[c]) << "channel " << "XYZ"[c];
    EXPECT_NEAR(s.mean, exact[c], 4.0 * s.stderr_) << "channel " << "XYZ"[c] << ": mean " << s.mean << " ± "
                                                    << s.stderr_ << ", exact " << exact[c];
  }
}

// ---------------------------------------------------------------------------------------------
// Mirror furnace: every bounce is the delta R/|cos θ| with probability 1, so a camera path of k
// bounces carries R^k·L_e and L = Σ_k R^k·L_e = L_e/(1 − R).

TEST(SpecularFurnace, MirrorIsLeOverOneMinusR) {
  auto scene = load("furnace_mirror.json");
  const Mirror& m = material<Mirror>(*scene, "mirror");
  const Fn Le = emission(*scene, 0);
  const Vec3 exact = toXyz(scene->range, [&](double l) { return Le(l) / (1.0 - m.reflectance()(float(l))); });
  expectAgreement(*scene, "pt", 1000, exact, 8, 128);
}

TEST(SpecularFurnace, MirrorEachPathLength) {
  // A depth limit d keeps Σ_{k ≤ d} R^k·L_e: each number of specular bounces on its own.
  auto scene = load("furnace_mirror.json");
  const Mirror& m = material<Mirror>(*scene, "mirror");
  const Fn Le = emission(*scene, 0);
  for (int d = 0; d <= 3; ++d) {
    const Vec3 exact = toXyz(scene->range, [&](double l) {
      const double R = m.reflectance()(float(l));
      return Le(l) * (1.0 - std::pow(R, d + 1)) / (1.0 - R);
    });
    expectAgreement(*scene, "pt", d, exact, 8, 64);
  }
}

// ---------------------------------------------------------------------------------------------
// Glass in a white furnace. Outside the glass the field is the furnace's L = L_e/(1 − r); inside
// it is n(λ)²·L, since basic radiance L/n² is conserved across the interface (Veach97 §5.2): the
// uniform field is the equilibrium of both sides and the glass is lossless.

double furnaceRadiance(const Scene& s, double l) {
  return emission(s, 0)(l) / (1.0 - material<Lambertian>(s, "wall").reflectance()(float(l)));
}

TEST(SpecularFurnace, GlassSphereSeenFromOutside) {
  // Every path into the glass comes out again: Fresnel splits without loss, the factors
  // (η_o/η_i)² of entering and leaving cancel. BK7 disperses, so each wavelength takes its own path.
  auto scene = load("furnace_glass.json");
  const Vec3 exact = toXyz(scene->range, [&](double l) { return furnaceRadiance(*scene, l); });
  expectAgreement(*scene, "pt", 1000, exact, 8, 128);
}

TEST(SpecularFurnace, InsideGlassRadianceIsNSquaredTimesL) {
  // The camera sits in the glass: each view path leaves it once more than it enters, so the
  // Radiance-mode factor (η_o/η_i)² = n² survives. Without it the image would be L, with it
  // inverted L/n².
  auto scene = load("furnace_glass_inside.json");
  const Ior& n = material<Dielectric>(*scene, "glass").ior();
  const Vec3 exact = toXyz(scene->range, [&](double l) { return sqr(n(float(l))) * furnaceRadiance(*scene, l); });
  expectAgreement(*scene, "pt", 1000, exact, 8, 128);
}

TEST(SpecularFurnace, DispersiveGlassWithHeroWavelengths) {
  // Hero wavelength sampling ends the secondary wavelengths at the first specular vertex (each
  // wavelength would refract its own way): outside and inside the glass the answers stay exact.
  for (const char* name : {"furnace_glass.json", "furnace_glass_inside.json"}) {
    SCOPED_TRACE(name);
    auto scene = load(name);
    scene->render.heroWavelengths = 4;
    const bool inside = std::string(name) == "furnace_glass_inside.json";
    const Ior& n = material<Dielectric>(*scene, "glass").ior();
    const Vec3 exact = toXyz(scene->range, [&](double l) {
      return (inside ? sqr(n(float(l))) : 1.0) * furnaceRadiance(*scene, l);
    });
    expectAgreement(*scene, "pt", 1000, exact, 8, 128);
  }
}

TEST(SpecularFurnace, NonDispersiveGlassKeepsEveryLane) {
  // A constant index refracts every wavelength the same way, so the lanes pass the specular
  // vertices together (each evaluates the same delta): outside and inside, the closed forms hold.
  for (const char* name : {"furnace_glass.json", "furnace_glass_inside.json"}) {
    SCOPED_TRACE(name);
    const std::string path = test::sourcePath("scenes/validation/" + std::string(name));
    nlohmann::json root = nlohmann::json::parse(test::readTextFile(path));
    root["materials"]["glass"]["ior"] = 1.5;
    auto scene = loadSceneFromJson(root, path);
    scene->render.heroWavelengths = 4;
    const double n2 = std::string(name) == "furnace_glass_inside.json" ? 1.5 * 1.5 : 1.0;
    const Vec3 exact = toXyz(scene->range, [&](double l) { return n2 * furnaceRadiance(*scene, l); });
    expectAgreement(*scene, "pt", 1000, exact, 8, 128);
  }
}

TEST(SpecularFurnace, ThinGlassSphereIsLossless) {
  // A thin BK7 shell: every path reflects or passes straight through without loss, so the field
  // stays L_e/(1 − r) (the camera sees only the shell: a path-tracer test, lanes ended at the
  // dispersive shell).
  const std::string path = test::sourcePath("scenes/validation/furnace_glass.json");
  nlohmann::json root = nlohmann::json::parse(test::readTextFile(path));
  root["materials"]["glass"]["type"] = "thin_dielectric";
  auto scene = loadSceneFromJson(root, path);
  const Vec3 exact = toXyz(scene->range, [&](double l) { return furnaceRadiance(*scene, l); });
  expectAgreement(*scene, "pt", 1000, exact, 8, 128);
}

class GlassEmitter : public ::testing::TestWithParam<const char*> {};

TEST_P(GlassEmitter, FieldStaysUniform) {
  // The core inside the glass emits the equilibrium radiance n²·L of the glass; its light reaches
  // the walls only through refraction out of the glass, in Radiance mode (path tracing) and in
  // Importance mode (light tracing, where the factor must not be applied).
  auto scene = load("furnace_glass_emitter.json");
  const Ior& n = material<Dielectric>(*scene, "glass").ior();
  for (const float l : {400.0f, 550.0f, 700.0f})
    ASSERT_NEAR(emission(*scene, 2)(l), sqr(n(l)) * furnaceRadiance(*scene, l), 1e-5)
        << "the scene's core must emit n²·L_e/(1 − r)";
  const Vec3 exact = toXyz(scene->range, [&](double l) { return furnaceRadiance(*scene, l); });
  // Light tracing reaches the small camera rarely: more and longer batches keep its power.
  const bool lt = std::string(GetParam()) == "lt";
  expectAgreement(*scene, GetParam(), 1000, exact, lt ? 16 : 8, lt ? 2048 : 128);
}

INSTANTIATE_TEST_SUITE_P(Integrators, GlassEmitter, ::testing::Values("pt", "lt"));

}  // namespace
}  // namespace kasha
