// libFuzzer target: the scene loader (scene/scene_loader.h) on arbitrary text. A scene is either
// loaded or rejected with an InputError (a message naming the file and the place); anything else
// (a crash, a sanitizer report, another exception, a hang, running out of memory) is a finding.
// A scene that loads is also rendered, 4×4 pixels at 1 sample with the path and light tracers:
// whatever a valid scene holds, rendering it must not crash or reach undefined behaviour, and
// no non-finite value may reach the film.
// Relative file names resolve in tests/fuzz/data/, which holds a spectrum, a matrix and a mesh.
// Built twice: fuzz_scene reads the text as kasha JSON (fuzz.json), fuzz_mitsuba as Mitsuba XML
// (fuzz.xml, through scene/mitsuba/).
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <stdexcept>
#include <string>

#include "core/error.h"
#include "core/film.h"
#include "scene/scene_loader.h"
#include "integrators/integrator_factory.h"
#include "integrators/render_loop.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace kasha;
  static const std::string path = std::string(KASHA_FUZZ_DATA_DIR) + "/" KASHA_FUZZ_SCENE_FILE;
  SceneLoadOptions options;
  options.memoryLimit = uint64_t(64) << 20;  // any file of the machine can be named: refuse large ones
  options.notes = nullptr;                   // the Mitsuba importer's approximations: not findings
  std::unique_ptr<Scene> scene;
  try {
    scene = loadSceneFromString(std::string(reinterpret_cast<const char*>(data), size), path, options);
  } catch (const InputError&) {
    return 0;
  }
  scene->camera = scene->camera.resized(4, 4);
  RenderSettings settings = scene->render;
  settings.maxDepth = std::min(settings.maxDepth, 6);
  for (const char* name : {"pt", "lt"}) {
    // Settings an integrator cannot use (a wavelength strategy at a site it never draws at, one
    // that would be biased for this scene) are refused with a message, as `kasha render` does.
    std::unique_ptr<Integrator> integrator;
    try {
      integrator = makeIntegrator(name, *scene, settings);
    } catch (const std::invalid_argument&) {
      continue;
    }
    Film film(4, 4);
    RenderOptions opt;
    opt.spp = 1;
    opt.threads = 1;
    opt.seed = settings.seed;
    opt.sampler = settings.sampler;
    render(*scene, *integrator, film, opt);
    for (int y = 0; y < 4; ++y)
      for (int x = 0; x < 4; ++x) {
        const Vec3 v = film.xyz(x, y);
        if (!std::isfinite(v.x) || !std::isfinite(v.y) || !std::isfinite(v.z)) {
          std::fprintf(stderr, "fuzz_scene: non-finite pixel (%d, %d) from %s\n", x, y, name);
          std::abort();
        }
      }
  }
  return 0;
}
