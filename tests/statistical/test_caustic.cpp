// The fluorescent caustic (scenes/uv_caustic.json): a UV point light reaches a fluorescent floor
// only through a glass sphere. Path tracing cannot render it; light tracing and BDPT (independent
// wavelengths) must agree with each other, region by region.
#include <gtest/gtest.h>

#include "scene/scene_loader.h"
#include "integrators/integrator_factory.h"
#include "tests/integrator_names.h"
#include "integrators/render_loop.h"
#include "tests/region_batches.h"
#include "tests/support.h"

namespace kasha {
namespace {

constexpr int kRes = 16, kRegions = 2;

std::unique_ptr<Scene> lowRes() {
  auto scene = loadScene(test::sourcePath("scenes/uv_caustic.json"));
  // Look straight at the caustic so that every region holds some of it.
  test::aimCamera(*scene, Vec3(0, 0, 0), 6.0f, kRes);
  test::setPhotons(*scene, 10000, 0.01f);  // photon mapping and vertex merging
  return scene;
}

std::vector<test::BatchStats> regions(const Scene& scene, const std::string& name, int spp, int batches) {
  const std::unique_ptr<Integrator> integrator = test::makeTestIntegrator(name, scene, scene.render);
  std::vector<std::vector<double>> per(kRegions * kRegions);
  for (int b = 0; b < batches; ++b) {
    Film film(kRes, kRes);
    RenderOptions opt;
    opt.spp = spp;
    opt.seed = 101 + uint64_t(b);
    render(scene, *integrator, film, opt);
    std::vector<double> sum(per.size(), 0.0);
    for (int y = 0; y < kRes; ++y)
      for (int x = 0; x < kRes; ++x) sum[size_t((y * kRegions / kRes) * kRegions + x * kRegions / kRes)] += film.xyz(x, y).y;
    for (size_t i = 0; i < per.size(); ++i) per[i].push_back(sum[i]);
  }
  std::vector<test::BatchStats> out;
  for (const auto& v : per) out.push_back(test::batchStats(v));
  return out;
}

TEST(FluorescentCaustic, PathTracingSeesNothing) {
  auto scene = lowRes();
  for (const test::BatchStats& r : regions(*scene, "pt", 16, 2)) EXPECT_EQ(r.mean, 0.0);
}

class FluorescentCausticAgreement : public ::testing::TestWithParam<std::pair<const char*, int>> {};

TEST_P(FluorescentCausticAgreement, WithLightTracing) {
  auto scene = lowRes();
  static const auto lt = regions(*scene, "lt", 256, 10);
  const auto bd = regions(*scene, GetParam().first, GetParam().second, 10);
  for (size_t i = 0; i < lt.size(); ++i) {
    const double sigma = std::hypot(lt[i].stderr_, bd[i].stderr_);
    EXPECT_GT(lt[i].mean, 0.0);
    EXPECT_LT(sigma, 0.1 * lt[i].mean) << "region " << i;
    EXPECT_NEAR(bd[i].mean, lt[i].mean, 4.0 * sigma) << "region " << i;
  }
}

INSTANTIATE_TEST_SUITE_P(Integrators, FluorescentCausticAgreement,
                         ::testing::Values(std::make_pair("bdpt", 128), std::make_pair("bdpt.both", 128), std::make_pair("bdpt-independent", 128),
                                           std::make_pair("ppm", 64)));
// Vertex connection and merging (issue 14): long under the sanitizers, which skip "Slow".
INSTANTIATE_TEST_SUITE_P(VertexMergingSlow, FluorescentCausticAgreement,
                         ::testing::Values(std::make_pair("vcm", 64), std::make_pair("bpm", 64)));

}  // namespace
}  // namespace kasha
