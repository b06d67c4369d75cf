// Jung18 fig. 1 (scenes/jung18_fig1.json): fluorescence gives colours outside the sRGB gamut. The
// paper reports a negative blue channel for its fluorescent sphere. With kasha's spectra (FPbase
// FITC, ColorChecker green, D65) the pure emission has negative blue *and* red, but the surface's
// reflected light adds enough blue that only its red channel stays negative; the plain sphere
// (same base reflectance) is inside the gamut. Checked in closed form for a patch of each material
// facing the scene's D65 light, then in kasha's own render of the scene.
#include <gtest/gtest.h>

#include <algorithm>
#include <memory>
#include <string>
#include <vector>

#include "core/color.h"
#include "scene/scene_loader.h"
#include "core/spectrum_presets.h"
#include "integrators/integrator_factory.h"
#include "integrators/render_loop.h"
#include "materials/jung_bbrrdf.h"
#include "tests/support.h"

namespace kasha {
namespace {

const JungBbrrdf& fluorescentMaterial(const Scene& scene) {
  for (size_t i = 0; i < scene.materialNames.size(); ++i)
    if (scene.materialNames[i] == "fluorescent_green") return dynamic_cast<const JungBbrrdf&>(*scene.materials[i]);
  throw std::runtime_error("no material fluorescent_green");
}

// Linear sRGB of the radiance leaving a patch under irradiance E = D65 (normal incidence), by
// 1 nm quadrature: L(λo) = [E(λo)(1 − c·a(λo))·r(λo) + c·Q·e(λo)·∫a(λ)E(λ)dλ] / π (Jung18 eq. 4
// integrated over λi); with fluorescence off (c = 0) it is the plain sphere's r·E/π.
enum class Part { Plain, Fluorescent, EmissionOnly };

Vec3 patchColour(const JungBbrrdf& m, Part part) {
  const Spectrum d65 = *presetSpectrum("D65");
  const float c = part == Part::Plain ? 0.0f : m.c();
  const double reflected = part == Part::EmissionOnly ? 0.0 : 1.0;
  double absorbed = 0.0;  // ∫ a·E over the scene's range (UV included)
  for (float l = m.range().min; l <= m.range().max; l += 1.0f) absorbed += m.a(l) * d65(l);
  const Observer& obs = Observer::cie1931();
  Vec3 xyz(0.0f);
  for (float l = 360.0f; l <= 830.0f; l += 1.0f) {
    const double radiance = (reflected * d65(l) * (1.0 - c * m.a(l)) * m.r(l) + c * m.q() * m.e(l) * absorbed) / kPi;
    xyz += obs.weight(l) * float(radiance);
  }
  return xyzToLinearSrgb(xyz);
}

TEST(Jung18Fig1, ClosedFormColoursOutsideTheGamutOnlyWithFluorescence) {
  const std::unique_ptr<Scene> scene = loadScene(test::sourcePath("scenes/jung18_fig1.json"));
  const JungBbrrdf& m = fluorescentMaterial(*scene);
  const Vec3 emission = patchColour(m, Part::EmissionOnly), fluorescent = patchColour(m, Part::Fluorescent),
             plain = patchColour(m, Part::Plain);
  auto str = [](const Vec3& v) { return std::to_string(v.x) + " " + std::to_string(v.y) + " " + std::to_string(v.z); };
  EXPECT_LT(emission.z, 0.0f) << "emission alone: sRGB " << str(emission);
  EXPECT_LT(emission.x, 0.0f) << "emission alone: sRGB " << str(emission);
  EXPECT_LT(fluorescent.x, 0.0f) << "fluorescent patch: sRGB " << str(fluorescent);
  EXPECT_GT(fluorescent.z, 0.0f) << "fluorescent patch: sRGB " << str(fluorescent);
  EXPECT_GT(std::min({plain.x, plain.y, plain.z}), 0.0f) << "plain patch: sRGB " << str(plain);
  EXPECT_GT(fluorescent.y, plain.y) << "fluorescence adds green";
}

// Mean linear sRGB over the pixels whose own and four neighbours' centre rays hit `shape`, one
// value per independent render (seed).
std::vector<Vec3> colourOfShape(const Scene& scene, const std::string& shape, int seeds) {
  const int w = scene.camera.width(), h = scene.camera.height();
  auto hits = [&](int x, int y) {
    const std::optional<Hit> hit = scene.accel->intersect(scene.camera.generateRay(Vec2(x + 0.5f, y + 0.5f), Vec2(0.5f)));
    return hit && scene.shapes[hit->shape].name == shape;
  };
  std::vector<std::pair<int, int>> pixels;
  for (int y = 1; y + 1 < h; ++y)
    for (int x = 1; x + 1 < w; ++x)
      if (hits(x, y) && hits(x - 1, y) && hits(x + 1, y) && hits(x, y - 1) && hits(x, y + 1)) pixels.push_back({x, y});
  EXPECT_GT(pixels.size(), 500u) << shape << " covers too few pixels";
  std::vector<Vec3> batches;
  const std::unique_ptr<Integrator> pt = makeIntegrator("pt", scene, scene.render);
  for (int s = 0; s < seeds; ++s) {
    Film film(w, h);
    RenderOptions opt;
    opt.spp = 4;
    opt.seed = uint64_t(101 + s);
    render(scene, *pt, film, opt);
    Vec3 sum(0.0f);
    for (const auto& [x, y] : pixels) sum += xyzToLinearSrgb(film.xyz(x, y));
    batches.push_back(sum / float(pixels.size()));
  }
  return batches;
}

test::BatchStats channel(const std::vector<Vec3>& batches, int c) {
  std::vector<double> v;
  for (const Vec3& b : batches) v.push_back(b[c]);
  return test::batchStats(v);
}

TEST(Jung18Fig1, RenderedFluorescentSphereHasNegativeRed) {
  const std::unique_ptr<Scene> scene = loadScene(test::sourcePath("scenes/jung18_fig1.json"));
  const std::vector<Vec3> fluorescent = colourOfShape(*scene, "fluorescent_sphere", 8);
  const std::vector<Vec3> plain = colourOfShape(*scene, "plain_sphere", 8);
  const test::BatchStats red = channel(fluorescent, 0);
  EXPECT_LT(red.mean + 4.0 * red.stderr_, 0.0) << "fluorescent sphere red " << red.mean << " ± " << red.stderr_;
  for (int c = 0; c < 3; ++c) {
    const test::BatchStats p = channel(plain, c);
    EXPECT_GT(p.mean - 4.0 * p.stderr_, 0.0) << "plain sphere channel " << c << ": " << p.mean << " ± " << p.stderr_;
  }
}

}  // namespace
}  // namespace kasha
