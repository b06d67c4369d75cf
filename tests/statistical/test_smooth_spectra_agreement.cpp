// Integrator agreement on a scene that is not a furnace, with smooth spectra everywhere (issue 13):
// scenes/validation/smooth_spectra.json — overlapping Gaussian absorption and emission on a diffuse
// and a coated (glossy) fluorescent sphere, a rough metal patch, a D65 panel and a Gaussian violet
// LED spot. With the sensor drawing mix:cmf,uniform and the light start mix:light,uniform wherever
// an integrator draws them, bdpt (both families), its families alone, lt, and vcm, vc and bpm
// (issue 14) agree with pt region by region within 4.5 standard errors (16 comparisons per
// integrator). And the unweighted images
// of bdpt's strategies that can each sample every path of a length agree with each other.
#include <gtest/gtest.h>

#include <array>
#include <fstream>
#include <map>

#include <nlohmann/json.hpp>

#include "integrators/bidirectional/strategy_images.h"
#include "integrators/integrator_factory.h"
#include "tests/integrator_names.h"
#include "integrators/render_loop.h"
#include "scene/scene_loader.h"
#include "tests/region_batches.h"
#include "tests/support.h"

namespace kasha {
namespace {

constexpr int kRes = 16, kRegions = 2;  // 2×2 regions of a 16×16 image

std::vector<test::BatchStats> estimate(const Scene& scene, const std::string& name, int spp, int batches) {
  RenderSettings settings = scene.render;
  // Vertex merging: its defaults scale with the pixel count, far too coarse for 16×16 pixels.
  settings.vcm.photonsPerPass = 10000;
  settings.vcm.radius = 0.02f;
  if (name != "lt") settings.wavelengths.sensor = parseWavelengthSpec("mix:cmf,uniform");
  if (name != "pt" && name != "bdpt-shared") settings.wavelengths.light = parseWavelengthSpec("mix:light,uniform");
  const std::unique_ptr<Integrator> integrator = test::makeTestIntegrator(name, scene, settings);
  return test::regionBatches(
      scene, *integrator, kRes, kRes, kRegions * kRegions,
      [](int x, int y) { return (y * kRegions / kRes) * kRegions + x * kRegions / kRes; }, spp, batches, 104729);
}

class SmoothSpectra : public ::testing::TestWithParam<std::pair<const char*, int>> {};

std::string testName(const ::testing::TestParamInfo<std::pair<const char*, int>>& info) {
  std::string n = info.param.first;
  for (char& ch : n)
    if (ch == '-' || ch == '.') ch = '_';
  return n;
}

TEST_P(SmoothSpectra, AgreesWithThePathTracerRegionByRegion) {
  const auto [name, spp] = GetParam();
  auto scene = loadScene(test::sourcePath("scenes/validation/smooth_spectra.json"));
  const Camera& c = scene->camera;
  scene->camera = Camera(c.position(), c.position() + c.forward(), Vec3(0, 1, 0), c.fovYDegrees(), kRes, kRes);
  static const std::vector<test::BatchStats> ref = estimate(*scene, "pt", 256, 12);
  const std::vector<test::BatchStats> other = estimate(*scene, name, spp, 12);
  for (size_t i = 0; i < ref.size(); ++i) {
    const double sigma = std::hypot(ref[i].stderr_, other[i].stderr_);
    EXPECT_LT(sigma, 0.05 * std::abs(ref[i].mean)) << "too noisy to compare, region/channel " << i;
    EXPECT_NEAR(other[i].mean, ref[i].mean, 4.5 * sigma) << name << ", region/channel " << i;
  }
}

// Without the (delta) spot light, the camera hitting the panel (s = 0), next-event estimation
// (s = 1) and the own-wavelength light tracing (t = 1) each sample every path of a length, so
// their unweighted images estimate the same thing: s0_t3, s1_t2, s2_t1_own on one-bounce paths,
// s0_t4, s1_t3, s3_t1_own on two-bounce ones (the shared family's t = 1 and joins would miss the
// fluorescent paths, the light vertex and own joins the elastic ones).
TEST(SmoothSpectraStrategies, UnweightedStrategiesOfTheSamePathsAgree) {
  std::ifstream in(test::sourcePath("scenes/validation/smooth_spectra.json"));
  nlohmann::json root = nlohmann::json::parse(in);
  root.erase("lights");
  root["camera"]["resolution"] = {kRes, kRes};
  const auto scene = loadSceneFromJson(root, test::sourcePath("scenes/validation/smooth_spectra.json"));
  RenderSettings settings = scene->render;
  settings.wavelengths.sensor = parseWavelengthSpec("mix:cmf,uniform");
  settings.wavelengths.light = parseWavelengthSpec("mix:light,uniform");
  settings.bdpt.families = BdptFamilies::Both;  // every strategy of both families, whatever a pilot would choose
  const std::unique_ptr<Integrator> bdpt = makeIntegrator("bdpt", *scene, settings);
  const std::vector<std::vector<std::string>> groups = {{"s0_t3", "s1_t2", "s2_t1_own"}, {"s0_t4", "s1_t3", "s3_t1_own"}};
  std::map<std::string, std::vector<std::vector<double>>> sums;  // strategy → region·3 + channel → batches
  constexpr int kBatches = 10;
  for (int b = 0; b < kBatches; ++b) {
    Film film(kRes, kRes);
    bidir::StrategyImages images(kRes, kRes, 3, scene->pixelFilter);
    RenderOptions opt;
    opt.spp = 512;
    opt.seed = 31 * uint64_t(b + 1);
    opt.strategies = [&](const StrategySample& r) { images.add(r); };
    render(*scene, *bdpt, film, opt);
    images.setSamplesPerPixel(film.samplesPerPixel());
    for (const auto& group : groups)
      for (const std::string& name : group) {
        ASSERT_TRUE(images.images().count(name)) << name;
        const Film& f = images.images().at(name)->unweighted;
        std::vector<std::vector<double>>& s = sums[name];
        s.resize(kRegions * kRegions * 3);
        std::vector<double> batch(s.size(), 0.0);
        for (int y = 0; y < kRes; ++y)
          for (int x = 0; x < kRes; ++x)
            for (int ch = 0; ch < 3; ++ch)
              batch[size_t(((y * kRegions / kRes) * kRegions + x * kRegions / kRes) * 3 + ch)] += f.xyz(x, y)[ch];
        for (size_t i = 0; i < s.size(); ++i) s[i].push_back(batch[i]);
      }
  }
  for (const auto& group : groups)
    for (size_t a = 0; a < group.size(); ++a)
      for (size_t b = a + 1; b < group.size(); ++b)
        for (size_t i = 0; i < kRegions * kRegions * 3; ++i) {
          const test::BatchStats x = test::batchStats(sums[group[a]][i]), y = test::batchStats(sums[group[b]][i]);
          const double sigma = std::hypot(x.stderr_, y.stderr_);
          EXPECT_LT(sigma, 0.1 * std::abs(x.mean)) << "too noisy to compare: " << group[a] << " " << group[b] << " " << i;
          EXPECT_NEAR(x.mean, y.mean, 4.5 * sigma) << group[a] << " vs " << group[b] << ", region/channel " << i;
        }
}

INSTANTIATE_TEST_SUITE_P(Integrators, SmoothSpectra,
                         ::testing::Values(std::make_pair("bdpt", 64), std::make_pair("bdpt.both", 64), std::make_pair("bdpt-shared", 64),
                                           std::make_pair("bdpt-independent", 64), std::make_pair("lt", 256)),
                         testName);
// Vertex connection and merging (issue 14): long under the sanitizers, which skip "Slow".
INSTANTIATE_TEST_SUITE_P(VertexMergingSlow, SmoothSpectra,
                         ::testing::Values(std::make_pair("vcm.bidirectional", 64), std::make_pair("vc", 64), std::make_pair("bpm", 64)),
                         testName);

}  // namespace
}  // namespace kasha
