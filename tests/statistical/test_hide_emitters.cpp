// render/hide_emitters (scene-format.md; Mitsuba's hide_emitters): paths without a scattering event
// contribute nothing, in every integrator. Seen directly, the emitter and the environment vanish;
// everything they light stays, so the integrators still agree with each other.
#include <gtest/gtest.h>

#include <array>

#include "integrators/integrator_factory.h"
#include "integrators/render_loop.h"
#include "scene/scene_loader.h"
#include "tests/integrator_names.h"
#include "tests/region_batches.h"
#include "tests/support.h"

namespace kasha {
namespace {

constexpr int kRes = 12, kRegions = 2;

// A two-sided emissive square in front of the camera over a lambertian floor it lights, and a
// constant environment: both emitters are seen directly.
std::unique_ptr<Scene> scene() {
  auto s = loadSceneFromString(R"({
    "render": {"spp": 1},
    "camera": {"position": [0, 1, -4], "look_at": [0, 0.6, 0], "fov": 50, "resolution": [12, 12]},
    "materials": {"white": {"type": "lambertian", "reflectance": 0.6}},
    "shapes": [{"type": "rectangle", "center": [0, 0, 0], "u": [0, 0, 3], "v": [3, 0, 0], "material": "white"},
               {"type": "rectangle", "center": [0, 1, 0.5], "u": [0.5, 0, 0], "v": [0, 0.5, 0], "material": "white",
                "emission": {"radiance": 2, "two_sided": true}}],
    "lights": [{"type": "environment", "radiance": 0.05}]
  })", "hide_emitters.json");
  test::setPhotons(*s, 2000, 0.05f);
  return s;
}

// The image's pixels (XYZ), row by row.
std::vector<Vec3> renderOnce(const Scene& s, const std::string& name, RenderSettings settings, int spp) {
  const std::unique_ptr<Integrator> integrator = test::makeTestIntegrator(name, s, settings);
  Film film(kRes, kRes);
  RenderOptions opt;
  opt.spp = spp;
  opt.seed = 3;
  render(s, *integrator, film, opt);
  std::vector<Vec3> pixels;
  for (int y = 0; y < kRes; ++y)
    for (int x = 0; x < kRes; ++x) pixels.push_back(film.xyz(x, y));
  return pixels;
}

TEST(HideEmitters, WithoutScatteringNothingIsLeft) {
  const auto s = scene();
  for (const char* name : {"pt", "lt", "bdpt", "ppm", "vcm", "vc", "bpm"}) {
    SCOPED_TRACE(name);
    RenderSettings settings = s->render;
    settings.maxDepth = 0;  // only the paths hide_emitters removes
    double seen = 0.0;
    for (const Vec3& v : renderOnce(*s, name, settings, 4)) seen += v.y;
    EXPECT_GT(seen, 0.0) << "the emitters are in view";
    settings.hideEmitters = true;
    const std::vector<Vec3> hidden = renderOnce(*s, name, settings, 4);
    for (size_t i = 0; i < hidden.size(); ++i) EXPECT_EQ(hidden[i], Vec3(0.0f)) << "pixel " << i;
  }
}

TEST(HideEmitters, TheLitSceneStaysAndTheIntegratorsAgree) {
  const auto s = scene();
  RenderSettings settings = s->render;
  settings.maxDepth = 3;
  settings.hideEmitters = true;
  const auto regionOf = [](int x, int y) { return (y * kRegions / kRes) * kRegions + x * kRegions / kRes; };
  const auto estimate = [&](const std::string& name, int spp) {
    const std::unique_ptr<Integrator> integrator = test::makeTestIntegrator(name, *s, settings);
    return test::regionBatches(*s, *integrator, kRes, kRes, kRegions * kRegions, regionOf, spp, 8, 7919);
  };
  const std::vector<test::BatchStats> pt = estimate("pt", 32);
  for (const char* name : {"lt", "bdpt", "vcm"}) {
    SCOPED_TRACE(name);
    test::expectRegionsAgree(pt, estimate(name, 16), 4.0, 0.1, 0.02);
  }
}

}  // namespace
}  // namespace kasha
