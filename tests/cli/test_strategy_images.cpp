// One image per BDPT strategy (integrators/bidirectional/strategy_images.h, `kasha render
// --strategy-images`): with the same seed the MIS-weighted images sum to the render pixel by
// pixel; an unweighted strategy that can sample every path is an estimator of the whole image on
// its own; the command line writes the files and refuses integrators without strategies.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>

#include <nlohmann/json.hpp>

#include "scene/scene_loader.h"
#include "integrators/bidirectional/strategy_images.h"
#include "integrators/integrator_factory.h"
#include "integrators/render_loop.h"
#include "tests/process.h"
#include "tests/integrator_names.h"
#include "tests/support.h"

namespace kasha {
namespace {

namespace fs = std::filesystem;

std::unique_ptr<Scene> load(const std::string& name) { return loadScene(test::sourcePath("scenes/validation/" + name)); }

// Renders with strategy records; `depth` is the longest path with images of its own.
bidir::StrategyImages renderWithStrategies(const Scene& scene, const std::string& integrator, int maxDepth, int depth,
                                          int spp, uint64_t seed, Film& film) {
  RenderSettings s = scene.render;
  s.maxDepth = maxDepth;
  const auto bdpt = test::makeTestIntegrator(integrator, scene, s);
  bidir::StrategyImages images(film.width(), film.height(), depth, scene.pixelFilter);
  RenderOptions opt;
  opt.spp = spp;
  opt.seed = seed;
  opt.strategies = [&](const StrategySample& r) { images.add(r); };
  render(scene, *bdpt, film, opt);
  images.setSamplesPerPixel(film.samplesPerPixel());
  return images;
}

// The MIS-weighted strategy images sum to the render, pixel by pixel.
void expectSumToTheRender(const bidir::StrategyImages& images, const Film& film) {
  for (int y = 0; y < film.height(); ++y)
    for (int x = 0; x < film.width(); ++x) {
      double sum[3] = {0, 0, 0}, magnitude = 0.0;
      for (const auto& [strategy, img] : images.images()) {
        const Vec3 v = img->weighted.xyz(x, y);
        for (int c = 0; c < 3; ++c) sum[c] += v[c], magnitude += std::abs(v[c]);
      }
      const Vec3 full = film.xyz(x, y);
      for (int c = 0; c < 3; ++c)
        ASSERT_NEAR(sum[c], full[c], 1e-5 * magnitude + 1e-7) << "pixel " << x << ", " << y << " channel " << c;
    }
}

TEST(StrategyImages, WeightedImagesSumToTheRender) {
  // The furnace with images up to 2 scattering events (longer paths go to "deeper"); the mirror
  // room (glass, floor, wall, mirror) up to 4, where only mollified connections (and merges) render it.
  for (const auto& [name, depth] : {std::pair{"furnace_fluorescent.json", 2}, std::pair{"mollify_mirror.json", 4}})
    for (const char* integrator : {"bdpt-shared", "bdpt-independent", "bdpt-mollified", "vcm.bidirectional", "bpm"}) {
      SCOPED_TRACE(std::string(name) + " " + integrator);
      auto scene = load(name);
      Film film(scene->camera.width(), scene->camera.height());
      const bidir::StrategyImages images = renderWithStrategies(*scene, integrator, 6, depth, 8, 11, film);
      if (depth == 2) EXPECT_TRUE(images.images().count("deeper"));
      if (depth == 2) EXPECT_GE(images.images().size(), 5u);
      if (depth == 4 && std::string(integrator) == "bdpt-mollified") EXPECT_TRUE(images.images().count("s3_t3_mollified"));
      if (depth == 2 && (std::string(integrator) == "vcm.bidirectional" || std::string(integrator) == "bpm"))  // all merges per camera vertex
        EXPECT_TRUE(images.images().count("merge_t2") && images.images().count("merge_t3"));
      expectSumToTheRender(images, film);
    }
}

// Medium vertices (docs/media.md §5, §6): a scattering, fluorescent medium around the camera, with
// bdpt's both families and vcm's merges in the volume.
TEST(StrategyImages, WeightedImagesSumToTheRenderInMedia) {
  for (const char* integrator : {"bdpt", "vcm.bidirectional"}) {
    SCOPED_TRACE(integrator);
    auto scene = load("media_fluorescent_furnace.json");
    Film film(scene->camera.width(), scene->camera.height());
    const bidir::StrategyImages images = renderWithStrategies(*scene, integrator, 6, 3, 8, 13, film);
    EXPECT_TRUE(images.images().count("s2_t2_own"));  // a join through a fluorescent collision
    if (std::string(integrator) != "bdpt") EXPECT_TRUE(images.images().count("merge_t2"));
    expectSumToTheRender(images, film);
  }
}

TEST(StrategyImages, UnweightedCameraPathsAloneEstimateTheImage) {
  // In a furnace whose walls emit, the camera path hitting an emitter (s = 0) can sample every
  // path: the sum over t of its unweighted images estimates the whole image, like path tracing
  // without next-event estimation. Depth 3 keeps every length in its own images.
  auto scene = load("furnace_overlap.json");
  std::vector<double> diff;
  for (int b = 0; b < 8; ++b) {
    Film film(scene->camera.width(), scene->camera.height());
    const bidir::StrategyImages images = renderWithStrategies(*scene, "bdpt-independent", 3, 3, 32, 70 + uint64_t(b), film);
    ASSERT_FALSE(images.images().count("deeper"));
    double s0 = 0.0;
    for (const auto& [strategy, img] : images.images())
      if (strategy.rfind("s0_", 0) == 0) s0 += img->unweighted.meanXyz().y;
    diff.push_back(s0 - film.meanXyz().y);
  }
  const test::BatchStats d = test::batchStats(diff);
  EXPECT_GT(d.stderr_, 0.0);
  EXPECT_NEAR(d.mean, 0.0, 4.0 * d.stderr_);
}

class StrategyImagesCli : public ::testing::Test {
 protected:
  void SetUp() override {
    ASSERT_TRUE(fs::is_regular_file(test::kKashaBinary)) << "build the kasha target first";
    dir = (fs::path(::testing::TempDir()) / ("kasha_strategy_images." + std::to_string(getpid()))).string();
    fs::create_directories(dir);
  }
  void TearDown() override {
    if (!HasFailure()) fs::remove_all(dir);
  }
  std::string dir;
};

TEST_F(StrategyImagesCli, WritesOneImagePerStrategy) {
  const std::string out = dir + "/strategies";
  const auto r = test::runKasha({"render", test::sourcePath("scenes/validation/furnace_fluorescent.json"), "-q", "--spp",
                                 "2", "--max-depth", "2", "--integrator", "bdpt", "--set", "bdpt.families=both", "--strategy-images", out,
                                 "--strategy-unweighted", "-o", dir + "/full.exr"},
                                dir + "/run");
  ASSERT_EQ(r.code, 0) << r.err;
  // Depth 2 in the furnace: s = 0, NEE and light tracing for each length, the light-vertex
  // strategy (the walls fluoresce), and the fluorescent connection s = 2, t = 2.
  for (const char* stem : {"s0_t2", "s0_t3", "s0_t4", "s1_t2", "s1_t3", "s2_t1", "s3_t1", "s1_t2_light_vertex", "s2_t2"})
    for (const char* ext : {".exr", ".png"}) {
      EXPECT_TRUE(fs::is_regular_file(out + "/" + stem + ext)) << stem << ext;
      EXPECT_TRUE(fs::is_regular_file(out + "/" + stem + "_unweighted" + ext)) << stem << ext;
    }
  const auto stats = nlohmann::json::parse(test::readTextFile(dir + "/full.stats.json"));
  EXPECT_EQ(stats["outputs"]["strategy_images"].size(), std::distance(fs::directory_iterator(out), fs::directory_iterator{}));
}

TEST_F(StrategyImagesCli, RefusesIntegratorsWithoutStrategies) {
  const std::string scene = test::sourcePath("scenes/validation/furnace_fluorescent.json");
  const auto pt = test::runKasha({"render", scene, "-q", "--integrator", "pt", "--strategy-images", dir + "/s", "-o",
                                  dir + "/pt.exr"},
                                 dir + "/run");
  EXPECT_EQ(pt.code, 2);  // a combination of options the integrator refuses
  EXPECT_NE(pt.err.find("--strategy-images"), std::string::npos) << pt.err;
  EXPECT_NE(pt.err.find("the integrator pt has no (s, t) strategies"), std::string::npos) << pt.err;
  EXPECT_FALSE(fs::exists(dir + "/pt.exr"));
  const auto moll = test::runKasha({"render", scene, "-q", "--integrator", "pt", "--set", "bdpt.mollify_bandwidth=5", "-o",
                                    dir + "/pt.exr"},
                                   dir + "/run");
  EXPECT_EQ(moll.code, 2);
  EXPECT_NE(moll.err.find("--set bdpt.mollify_bandwidth=5: only for --integrator bdpt"), std::string::npos) << moll.err;
  const auto alpha = test::runKasha({"render", scene, "-q", "--integrator", "bdpt-mollified", "--set", "bdpt.mollify_alpha=1.5"},
                                    dir + "/run");
  EXPECT_EQ(alpha.code, 2);
  EXPECT_NE(alpha.err.find("--set bdpt.mollify_alpha=1.5: must be in (0, 1)"), std::string::npos) << alpha.err;
  // An alias names the integrator it stands for, and its settings are its own.
  EXPECT_NE(alpha.err.find("kasha: note: --integrator bdpt-mollified stands for --integrator bdpt --set bdpt.families=own "
                           "--set bdpt.mollify=true"),
            std::string::npos)
      << alpha.err;
  const auto families = test::runKasha({"render", scene, "-q", "--integrator", "bdpt-mollified", "--set", "bdpt.families=both"},
                                       dir + "/run");
  EXPECT_EQ(families.code, 2);
  EXPECT_NE(families.err.find("--set bdpt.families=both: the integrator bdpt-mollified stands for bdpt with bdpt.families=own"),
            std::string::npos)
      << families.err;
}

}  // namespace
}  // namespace kasha
