// vcm's choice between every strategy, the connections alone and camera paths alone (docs/bdpt-mis.md
// §14): the densities of the connections alone and of camera paths alone from the weights' sums,
// what stratified random numbers gain, the pilot's decision on scenes whose light camera paths find
// or miss, and that the connections alone and camera paths alone are exactly vc's and pt's
// estimators.
#include <gtest/gtest.h>

#include <cmath>
#include <set>
#include <tuple>

#include "integrators/bidirectional/pilot_observer.h"
#include "integrators/bidirectional/family_pilot.h"
#include "integrators/integrator_factory.h"
#include "integrators/render_loop.h"
#include "integrators/bidirectional/vcm.h"
#include "scene/scene_loader.h"
#include "tests/support.h"

namespace kasha {
namespace {

// Sums and factors whose combination is worked out by hand below: hit … ownSplat = 1 … 6, the
// merges' terms 7 … 10 (0 without merges); σ = 0.5, g = 2, κ = 0.25, S = 0.5, ℓ = 3, ε_h = 0.1.
bidir::MisSums sumsByHand(bool merges) {
  bidir::MisSums m;
  m.hit = 1.0, m.nee = 2.0, m.shared = 3.0, m.own = 4.0, m.mollified = 5.0, m.ownSplat = 6.0;
  if (merges) m.mergeShared = 7.0, m.mergeOwn = 8.0, m.mergeMollified = 9.0, m.mergeOwnSplat = 10.0;
  return m;
}
bidir::MisFactors factorsByHand() {
  bidir::MisFactors f;
  f.sharedFamily = f.ownFamily = true;
  f.oneGroup = true;
  f.sensorPdf = 0.5, f.laneGain = 2.0, f.cameraChoice = 0.25, f.sharedChoice = 0.5, f.ownChoice = 3.0;
  f.mollifyWidth = 0.1;
  return f;
}

// ρ = p_vcm/p_camera from the power-heuristic sums: camera paths alone keep the camera subpath
// reaching the light and next-event estimation (σ²·g²·(hit + κ²·nee)), every other term goes.
TEST(VcmPaths, TheDensityOfCameraPathsAlone) {
  const bidir::MisSums total = sumsByHand(false);
  const bidir::MisFactors f = factorsByHand();
  // σ²·(g²·(1 + κ²·2 + S²·3) + ℓ²·(4 + ε²·5)) + ℓ²·6, and σ²·g²·(1 + κ²·2).
  const double all = 0.25 * (4.0 * (1.0 + 0.0625 * 2.0 + 0.25 * 3.0) + 9.0 * (4.0 + 0.01 * 5.0)) + 9.0 * 6.0;
  const double camera = 0.25 * 4.0 * (1.0 + 0.0625 * 2.0);
  ASSERT_NEAR(bidir::combine(total, f), all, 1e-12);
  EXPECT_NEAR(bidir::densityOverAlone(bidir::Alone::Camera, total, f, all, 0.0), std::sqrt(all / camera), 1e-12);
  // A path neither the camera subpath's hit nor next-event estimation samples.
  bidir::MisSums joinsOnly;
  joinsOnly.shared = 1.0;
  EXPECT_TRUE(std::isinf(bidir::densityOverAlone(bidir::Alone::Camera, joinsOnly, f, 1.0, 0.0)));
}

// ρ = p_vcm/p_vc: the connections alone keep every term but the merges', which enter the sum with
// the factors of their namesakes, and the mollified joins' (vc has no wavelength kernel).
TEST(VcmPaths, TheDensityOfTheConnectionsAlone) {
  const bidir::MisSums total = sumsByHand(true);
  const bidir::MisFactors f = factorsByHand();
  // σ²·(g²·(1 + κ²·2 + S²·(3 + 7)) + ℓ²·(4 + 8 + ε²·(5 + 9))) + ℓ²·(6 + 10), and without 5 and 7–10.
  const double all = 0.25 * (4.0 * (1.0 + 0.0625 * 2.0 + 0.25 * 10.0) + 9.0 * (12.0 + 0.01 * 14.0)) + 9.0 * 16.0;
  const double connections = 0.25 * (4.0 * (1.0 + 0.0625 * 2.0 + 0.25 * 3.0) + 9.0 * 4.0) + 9.0 * 6.0;
  ASSERT_NEAR(bidir::combine(total, f), all, 1e-12);
  EXPECT_NEAR(bidir::densityOverAlone(bidir::Alone::Connections, total, f, all, 0.0), std::sqrt(all / connections),
              1e-12);
  // A path only a merge samples (a caustic seen through a specular vertex).
  bidir::MisSums mergesOnly;
  mergesOnly.mergeShared = 1.0;
  EXPECT_TRUE(std::isinf(bidir::densityOverAlone(bidir::Alone::Connections, mergesOnly, f, 1.0, 0.0)));
}

// 1 + U(−1, 1) per channel: Var = 1/3 around a mean of 1; stratified over a pixel's samples (Sobol)
// the mean's variance falls faster than 1/n.
Vec3 noisy(Sampler& rng) { return Vec3(1.0f) + 2.0f * rng.uniform3() - Vec3(1.0f); }

TEST(VcmPaths, RelativeVarianceAtPixelsIsKnownAndStratificationLowersIt) {
  const bidir::PilotSample sample = [](Vec2, Sampler& rng, SampleContext& ctx, std::vector<std::vector<Splat>>&) {
    ++ctx.counter.closest;
    return noisy(rng);
  };
  RayCounter rays;
  constexpr int spp = 16;
  constexpr size_t pixels = 2048;
  const double independent =
      bidir::relativeVarianceAtPixels(64, 64, 3, SamplerKind::Independent, spp, pixels, sample, rays);
  EXPECT_EQ(rays.closest, uint64_t(2 * spp * pixels));
  // Σ_XYZ (1/3)/(1 + 10⁻²), m ≈ 1 up to its noise; the standard error of the mean over the pixels of
  // Σ_XYZ spp·(x₁ − x₂)²/2 with x₁ − x₂ normal of variance 2/(3·spp): √(3·2/pixels)·(1/3).
  const double expected = 3.0 * (1.0 / 3.0) / 1.01;
  EXPECT_NEAR(independent, expected, 4.0 * std::sqrt(6.0 / pixels) / 3.0 + 0.01);
  const double stratified = bidir::relativeVarianceAtPixels(64, 64, 3, SamplerKind::Sobol, spp, pixels, sample, rays);
  EXPECT_LT(stratified, 0.5 * independent);  // a smooth integrand in 3 dimensions at 16 samples
}

TEST(VcmPaths, ThePixelsOfTheStratificationEstimateCoverTheImage) {
  // 512 pixels of a 512×512 image once fell on its first column (j·all/pixels): a 23 × 23 grid now.
  for (const auto& [w, h, n] : {std::tuple{512, 512, 512}, {256, 144, 512}, {64, 64, 2048}, {7, 3, 21}}) {
    const std::vector<Vec2> at = bidir::spreadPixels(w, h, size_t(n));
    ASSERT_EQ(at.size(), size_t(n));
    std::set<float> xs, ys;
    std::set<std::pair<float, float>> distinct;
    for (const Vec2& p : at) {
      EXPECT_TRUE(p.x >= 0.0f && p.x < float(w) && p.y >= 0.0f && p.y < float(h)) << p.x << ", " << p.y;
      xs.insert(p.x), ys.insert(p.y), distinct.insert({p.x, p.y});
    }
    EXPECT_EQ(distinct.size(), size_t(n)) << w << "x" << h;
    EXPECT_GE(double(xs.size()), 0.7 * std::sqrt(double(n) * w / h)) << w << "x" << h;
    EXPECT_GE(double(ys.size()), 0.7 * std::sqrt(double(n) * h / w)) << w << "x" << h;
  }
}

std::unique_ptr<Scene> smallScene(const char* file, int res) {
  auto scene = loadScene(test::sourcePath(file));
  const Camera& c = scene->camera;
  scene->camera = Camera(c.position(), c.position() + c.forward(), c.up(), c.fovYDegrees(), res, res);
  return scene;
}

VcmPaths pilotChoice(const Scene& scene) {
  RenderSettings settings = scene.render;
  settings.vcm.paths = VcmPaths::Auto;
  const std::unique_ptr<Integrator> in = makeIntegrator("vcm", scene, settings);
  RayCounter rays;
  return dynamic_cast<const Vcm&>(*in).pilotChoice(scene, 1, rays);
}

// uv_caustic.json: a UV point lamp's light reaches the fluorescent floor only through glass, which
// no camera path can sample; the floor, seen directly, fluoresces: the wide gather. Jung18 fig. 3:
// fluorescent spheres seen directly under a distant UV light, which camera paths cannot sample
// either: the wide gather. uv_caustic_mirror.json: the caustic through a lens from a small LED,
// which camera paths through the lens hit too rarely. The Cornell box lit by a visible lamp: diffuse
// light that camera paths with next-event estimation find well, at a third of vcm's rays.
TEST(VcmPaths, ThePilotKeepsLightSubpathsWhereCameraPathsMissTheLight) {
  EXPECT_EQ(pilotChoice(*smallScene("scenes/uv_caustic.json", 48)), VcmPaths::Gather);
  EXPECT_EQ(pilotChoice(*smallScene("scenes/jung18_fig3.json", 48)), VcmPaths::Gather);
  EXPECT_EQ(pilotChoice(*smallScene("scenes/yamamoto_leds.json", 48)), VcmPaths::Gather);
  EXPECT_NE(pilotChoice(*smallScene("scenes/uv_caustic_mirror.json", 48)), VcmPaths::Camera);
  EXPECT_EQ(pilotChoice(*smallScene("scenes/cornell_fluorescent.json", 48)), VcmPaths::Camera);
}

std::vector<Vec3> image(const Scene& scene, const std::string& name, RenderSettings settings, RenderStats* stats) {
  Film film(scene.camera.width(), scene.camera.height());
  RenderOptions opt;
  opt.spp = 4;
  opt.seed = 9;
  const RenderStats st = render(scene, *makeIntegrator(name, scene, settings), film, opt);
  if (stats) *stats = st;
  std::vector<Vec3> out;
  for (int y = 0; y < film.height(); ++y)
    for (int x = 0; x < film.width(); ++x) out.push_back(film.xyz(x, y));
  return out;
}

// vcm with its paths fixed to `paths`, and with the pilot choosing them, renders the image of
// `estimator` from the same seed, and the pilot reports `paths`; their statistics go to `fixed` and
// `chosen`.
void expectVcmRunsAlone(const Scene& scene, const std::string& estimator, VcmPaths paths, RenderStats& fixed,
                        RenderStats& chosen) {
  RenderSettings settings = scene.render;
  const std::vector<Vec3> expected = image(scene, estimator, settings, nullptr);
  settings.vcm.paths = paths;
  EXPECT_EQ(image(scene, "vcm", settings, &fixed), expected);
  settings.vcm.paths = VcmPaths::Auto;
  EXPECT_EQ(image(scene, "vcm", settings, &chosen), expected);
  const std::string report = std::string("paths: ") + toString(paths) +
                             " (pilot: relative variance per sample and cost per sample in rays: bidirectional ";
  EXPECT_EQ(chosen.choices.rfind(report, 0), 0u) << chosen.choices;
}

// Camera paths alone, fixed or chosen by the pilot, are pt's estimator; the decision is reported.
TEST(VcmPaths, CameraPathsAloneArePt) {
  RenderStats fixed, chosen;
  expectVcmRunsAlone(*smallScene("scenes/cornell_fluorescent.json", 24), "pt", VcmPaths::Camera, fixed, chosen);
  EXPECT_EQ(fixed.choices, "paths: camera");
  // The pilot's rays count with the render's.
  EXPECT_GT(chosen.closestRays, fixed.closestRays);
}

// The connections alone, fixed or chosen by the pilot, are vc's estimator. uv_dye_caustic.json: the
// LED's light reaches the dye through a lens and a window, and the camera sees the beam directly:
// light tracing's connections carry it, merges add nothing there but their cost
// (docs/convergence.md, media scenes), and camera paths cannot sample it.
TEST(VcmPaths, TheConnectionsAloneAreVc) {
  RenderStats fixed, chosen;
  expectVcmRunsAlone(*smallScene("scenes/uv_dye_caustic.json", 24), "vc", VcmPaths::Connections, fixed, chosen);
}

TEST(VcmPaths, FixedOrHalvesDecideNothing) {
  const auto scene = smallScene("scenes/uv_caustic.json", 16);
  RenderSettings settings = scene->render;
  settings.vcm.paths = VcmPaths::Bidirectional;
  EXPECT_EQ(makeIntegrator("vcm", *scene, settings)->choices(), "");
  settings.vcm.paths = VcmPaths::Auto;
  EXPECT_EQ(makeIntegrator("vc", *scene, settings)->choices(), "");
  EXPECT_EQ(makeIntegrator("bpm", *scene, settings)->choices(), "");
  RenderStats st;
  image(*scene, "vcm", settings, &st);
  // The pilot chose light subpaths (which of the two depends on its noise at 16×16 pixels).
  EXPECT_TRUE(st.choices.rfind("paths: gather (pilot: ", 0) == 0 || st.choices.rfind("paths: bidirectional (pilot: ", 0) == 0)
      << st.choices;
  EXPECT_NE(st.choices.find("camera alone cannot sample some paths that carry light"), std::string::npos) << st.choices;
  // Without fluorescence there are no own light vertices: the wide gather is vcm itself, not measured.
  const auto elastic = smallScene("scenes/validation/smooth_sphere_distant.json", 16);
  image(*elastic, "vcm", elastic->render, &st);
  EXPECT_NE(st.choices.find("; gather the same (no own light vertices); "), std::string::npos) << st.choices;
}

}  // namespace
}  // namespace kasha
