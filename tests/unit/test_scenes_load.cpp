// Every scene shipped in scenes/ (the published scenes of docs/report, the Cornell boxes and the
// validation scenes) loads without error, and each published scene builds an integrator of every
// kind the convergence harness runs. Loading only: rendering them is bench/convergence/'s job.
// scenes/materials/ holds material files (`{"type": "file"}`), not scenes.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

#include "scene/scene_loader.h"
#include "integrators/integrator_factory.h"

namespace kasha {
namespace {

namespace fs = std::filesystem;

std::vector<std::string> sceneFiles() {
  std::vector<std::string> files;
  const fs::path materials = fs::path(KASHA_SOURCE_DIR "/scenes/materials");
  for (const auto& e : fs::recursive_directory_iterator(KASHA_SOURCE_DIR "/scenes"))
    if (e.is_regular_file() && e.path().extension() == ".json" && e.path().parent_path() != materials)
      files.push_back(e.path().string());
  return files;
}

TEST(Scenes, EverySceneLoads) {
  const std::vector<std::string> files = sceneFiles();
  EXPECT_GE(files.size(), 5u) << "scenes/ is missing scenes";
  for (const std::string& f : files) {
    SCOPED_TRACE(f);
    std::unique_ptr<Scene> scene;
    EXPECT_NO_THROW(scene = loadScene(f));
    if (scene) EXPECT_GT(scene->camera.width() * scene->camera.height(), 0);
  }
}

TEST(Scenes, PublishedScenesBuildEveryIntegrator) {
  for (const char* name : {"jung18_fig1", "jung18_fig3", "jung18_fig4", "yamamoto_leds", "viewing_booth"}) {
    const std::string f = std::string(KASHA_SOURCE_DIR "/scenes/") + name + ".json";
    SCOPED_TRACE(f);
    ASSERT_TRUE(fs::is_regular_file(f));
    const std::unique_ptr<Scene> scene = loadScene(f);
    for (const char* integrator : {"pt", "lt", "bdpt-shared", "bdpt-independent", "ppm"})
      EXPECT_NE(makeIntegrator(integrator, *scene, scene->render), nullptr) << integrator;
  }
}

}  // namespace
}  // namespace kasha
