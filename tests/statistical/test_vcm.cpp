// Vertex connection and merging's settings and passes (integrators/bidirectional/, docs/bdpt-mis.md §12):
// its defaults, the memory limit of a pass's light vertices, bit-identical images for any number
// of threads, and the settings it refuses.
#include <gtest/gtest.h>

#include <cmath>

#include "core/memory_budget.h"
#include "integrators/integrator_factory.h"
#include "integrators/progressive_schedule.h"
#include "integrators/render_loop.h"
#include "integrators/bidirectional/light_vertex_pass.h"
#include "integrators/bidirectional/vcm.h"
#include "scene/scene_loader.h"
#include "tests/integrator_names.h"
#include "tests/support.h"

namespace kasha {
namespace {

std::unique_ptr<Scene> load(const std::string& name) { return loadScene(test::sourcePath("scenes/validation/" + name)); }

TEST(Vcm, DefaultsComeFromTheScene) {
  auto scene = load("furnace_fluorescent.json");
  const Vcm vcm(*scene, scene->render, Vcm::Parts::ConnectionsAndMerges);
  const size_t pixels = size_t(scene->camera.width()) * size_t(scene->camera.height());
  EXPECT_EQ(vcm.lightPathsPerPass(), pixels);
  // One light vertex in a disc if a pass's covered the sphere's area 4π evenly: a subpath keeps
  // several in the furnace (its walls reflect 60–90%), so the radius is below one vertex per path's.
  const double onePerPath = std::sqrt(4.0 * kPi / (kPi * double(pixels)));
  EXPECT_LT(vcm.radius(0), 0.8 * onePerPath);
  EXPECT_GT(vcm.radius(0), 0.2 * onePerPath);
  EXPECT_NEAR(vcm.radius(99) / vcm.radius(0), std::sqrt(progressiveRadiusSquared(1.0f, 2.0f / 3.0f, 100)), 1e-6);
  RenderSettings s = scene->render;
  s.vcm.radius = 0.05f;  // render/vcm/radius: the first pass's, as given
  EXPECT_FLOAT_EQ(Vcm(*scene, s, Vcm::Parts::Merges).radius(0), 0.05f);
  EXPECT_EQ(vcm.name(), "vcm");
  EXPECT_EQ(makeIntegrator("vc", *scene, scene->render)->name(), "vc");
  EXPECT_EQ(makeIntegrator("bpm", *scene, scene->render)->name(), "bpm");
}

TEST(Vcm, RefusesWhatItCannotDo) {
  auto scene = load("furnace_fluorescent.json");
  RenderSettings s = scene->render;
  s.heroWavelengths = bidir::kLightVertexLanes + 1;  // a light vertex keeps 4 lanes
  EXPECT_THROW(makeIntegrator("vcm", *scene, s), std::invalid_argument);
  s = scene->render;
  s.vcm.alpha = 0.3f;  // the kernel in wavelength needs α > 1/3
  EXPECT_THROW(makeIntegrator("bpm", *scene, s), std::invalid_argument);
  s = scene->render;
  s.vcm.radius = -1.0f;
  EXPECT_THROW(makeIntegrator("vc", *scene, s), std::invalid_argument);
}

TEST(Vcm, MemoryLimitIsCheckedAsTheLightVerticesAccumulate) {
  auto scene = load("furnace_fluorescent.json");
  RenderSettings s = scene->render;
  s.vcm.photonsPerPass = 3000;
  s.memoryLimit = 2000 * kBytesPerLightVertex;  // a furnace keeps several vertices per subpath
  const std::unique_ptr<Integrator> bpm = makeIntegrator("bpm", *scene, s);
  Film film(scene->camera.width(), scene->camera.height());
  RenderOptions opt;
  opt.spp = 1;
  EXPECT_THROW(render(*scene, *bpm, film, opt), MemoryLimitError);
}

TEST(Vcm, ImageDoesNotDependOnTheThreadCount) {
  auto scene = load("furnace_overlap.json");
  RenderSettings s = scene->render;
  s.vcm.photonsPerPass = 5000;  // several chunks of light subpaths
  for (const char* name : {"vcm", "vcm.bidirectional", "bpm"}) {  // vcm: its pilot's choice as well
    const std::unique_ptr<Integrator> integrator = test::makeTestIntegrator(name, *scene, s);
    std::vector<Vec3> images[2];
    for (int t = 0; t < 2; ++t) {
      Film film(scene->camera.width(), scene->camera.height());
      RenderOptions opt;
      opt.spp = 3;
      opt.threads = t + 1;
      render(*scene, *integrator, film, opt);
      for (int y = 0; y < film.height(); ++y)
        for (int x = 0; x < film.width(); ++x) images[t].push_back(film.xyz(x, y));
    }
    EXPECT_EQ(images[0], images[1]) << name;
  }
}

}  // namespace
}  // namespace kasha
