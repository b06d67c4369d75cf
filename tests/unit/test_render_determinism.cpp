// Reproducibility: an image depends on the seed only, never on the number of threads.
#include <gtest/gtest.h>

#include "scene/scene_loader.h"
#include "integrators/integrator_factory.h"
#include "integrators/render_loop.h"
#include "tests/support.h"

namespace kasha {
namespace {

std::vector<Vec3> renderCornell(int threads, uint64_t seed) {
  auto scene = loadScene(test::sourcePath("scenes/cornell_fluorescent.json"));
  const std::unique_ptr<Integrator> pt = makeIntegrator("pt", *scene, scene->render);  // default lanes
  Film film(scene->camera.width(), scene->camera.height());
  RenderOptions opt;
  opt.spp = 2;
  opt.seed = seed;
  opt.threads = threads;
  render(*scene, *pt, film, opt);
  std::vector<Vec3> px;
  for (int y = 0; y < film.height(); ++y)
    for (int x = 0; x < film.width(); ++x) px.push_back(film.xyz(x, y));
  return px;
}

TEST(RenderDeterminism, OneAndTwoThreadsGiveIdenticalImages) {
  const std::vector<Vec3> a = renderCornell(1, 42), b = renderCornell(2, 42);
  ASSERT_EQ(a.size(), b.size());
  size_t differing = 0;
  for (size_t i = 0; i < a.size(); ++i) differing += (a[i] != b[i]);
  EXPECT_EQ(differing, 0u) << "bit-identical pixels expected";
}

TEST(RenderDeterminism, SeedChangesTheImage) {
  const std::vector<Vec3> a = renderCornell(2, 1), b = renderCornell(2, 2);
  size_t differing = 0;
  for (size_t i = 0; i < a.size(); ++i) differing += (a[i] != b[i]);
  EXPECT_GT(differing, a.size() / 2);
}

}  // namespace
}  // namespace kasha
