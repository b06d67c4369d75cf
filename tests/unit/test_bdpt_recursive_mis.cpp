// BDPT's recursive MIS weights (docs/bdpt-mis.md §9) against the full recomputation over the whole
// path (integrators/bidirectional/mis.h, §5): on subpaths traced in scenes with area, point, spot, distant
// and environment lights, elastic, fluorescent, glossy and specular vertices, every connection's
// weight computed both ways must agree (relative 1e-5), for each wavelength family alone and both
// together, with and without spectral mollification, and with wavelength lanes; through the pinhole,
// a thin lens and an orthographic camera.
#include <gtest/gtest.h>

#include "integrators/bidirectional/connect.h"
#include "integrators/bidirectional/subpaths.h"
#include "scene/scene_loader.h"
#include "scene/wavelength_strategy.h"
#include "tests/support.h"
#include "tests/weight_checks.h"

namespace kasha::bidir {
namespace {

// The scene's own camera, or in its frame a thin lens (focused in front of the Cornell box, radius
// 30 mm) or an orthographic camera (a 400 × 400 mm film).
enum class CameraKind { Scene, ThinLens, Orthographic };

void replaceCamera(Scene& scene, CameraKind kind) {
  const Camera& c = scene.camera;
  const Vec3 at = c.position() + c.forward();
  if (kind == CameraKind::ThinLens)
    scene.camera = Camera::thinLens(c.position(), at, c.up(), c.fovYDegrees(), c.width(), c.height(), 30.0f, 500.0f);
  if (kind == CameraKind::Orthographic)
    scene.camera = Camera::orthographic(c.position(), at, c.up(), Vec2(400.0f), c.width(), c.height());
}

struct Case {
  const char* scene;
  Families families;
  float bandwidth;  // mollification's kernel half-width (nm), 0: none
  int lanes = 1;    // wavelength lanes per camera sample (docs/bdpt-mis.md §10)
  bool merged = false;  // both families on one light subpath (the unified estimator, §11)
  CameraKind camera = CameraKind::Scene;
};

std::string describe(const Case& c) {
  return std::string(c.scene) + (c.families.shared ? " shared" : "") + (c.families.independent ? " own" : "") +
         (c.bandwidth > 0.0f ? " mollified" : "") + (c.lanes > 1 ? " lanes " + std::to_string(c.lanes) : "") +
         (c.merged ? " merged" : "") + (c.camera == CameraKind::ThinLens       ? " thin lens"
                                        : c.camera == CameraKind::Orthographic ? " orthographic"
                                                                               : "");
}

class RecursiveWeights : public ::testing::TestWithParam<Case> {};

TEST_P(RecursiveWeights, EqualTheFullRecomputation) {
  const Case& param = GetParam();
  const auto scene = loadScene(test::sourcePath(param.scene));
  replaceCamera(*scene, param.camera);
  const WavelengthSources sources(*scene);
  const WavelengthStrategy sensor(scene->render.wavelengths.sensor, sources, WavelengthSite::Sensor);
  const WavelengthStrategy light(scene->render.wavelengths.light, sources, WavelengthSite::LightStart);
  const LightFirstStart lightFirst(*scene, scene->render.wavelengths.light);
  const WalkSettings ws{6, 3, &light.density(), param.merged ? &lightFirst : nullptr, {}};  // paths up to 6 scattering vertices
  std::vector<PathVertex> C, LS, LO;
  test::WeightOracle oracle;
  LaneTables laneTables;
  std::vector<Splat> splats;
  RayCounter counter;
  test::WeightTally tally;
  for (uint32_t sample = 0; sample < 20000; ++sample) {
    Sampler rng(SamplerKind::Independent, 11, sample, 0);
    const Lanes lanes = sensorLanes(*scene, sensor.density(), rng.uniform(), param.lanes, laneTables,
                                    param.families.independent ? &light.density() : nullptr,
                                    param.merged ? &lightFirst : nullptr);
    if (lanes.pdf[0] <= 0.0f) continue;
    const Vec2 film(rng.uniform() * float(scene->camera.width()), rng.uniform() * float(scene->camera.height()));
    traceCameraSubpath(*scene, film, lanes, ws, rng, counter, C);
    LS.clear(), LO.clear();
    int sharedLightVertices = 0;
    if (param.merged) {
      sharedLightVertices = traceMergedLightSubpath(*scene, lanes, ws, rng, counter, LS, LO);
    } else {
      if (param.families.shared) traceLightSubpath(*scene, LightFamily::Shared, lanes, ws, rng, counter, LS);
      if (param.families.independent) traceLightSubpath(*scene, LightFamily::Own, lanes, ws, rng, counter, LO);
    }
    Context c{*scene, ws, param.families, lanes, sensor.density(), counter};
    c.sharedLightVertices = sharedLightVertices;
    c.bandwidth = param.bandwidth;
    c.observer = &oracle;
    oracle.checks.clear();
    splats.clear();
    float radiance[kMaxLanes];
    Vec3 xyz;
    connectSubpaths(c, C, LS, LO, rng, splats, radiance, xyz);
    ASSERT_TRUE(tally.add(oracle.checks, sample)) << describe(param);
  }
  tally.expectPower(2000, describe(param));
}

constexpr Families kShared{true, false}, kOwn{false, true}, kBoth{true, true};

INSTANTIATE_TEST_SUITE_P(
    Scenes, RecursiveWeights,
    ::testing::Values(Case{"scenes/cornell_uv.json", kBoth, 0.0f},            // area lights, UV spot, fluorescence
                      Case{"scenes/cornell_uv.json", kOwn, 0.0f},
                      Case{"scenes/cornell_uv.json", kShared, 0.0f},
                      Case{"scenes/cornell_uv.json", kOwn, 20.0f},            // mollified joins
                      Case{"scenes/cornell_glossy.json", kBoth, 0.0f},        // glossy, elastic
                      Case{"scenes/uv_caustic.json", kBoth, 0.0f},            // glass: specular vertices
                      Case{"scenes/validation/furnace_point_light.json", kBoth, 0.0f},      // a point light
                      Case{"scenes/validation/smooth_sphere_distant.json", kBoth, 0.0f},    // a distant light
                      Case{"scenes/validation/single_sphere_environment.json", kBoth, 0.0f},  // environment
                      Case{"scenes/validation/mollify_mirror.json", kBoth, 30.0f},         // mirror, glass, point
                      // Lanes: ended at fluorescent and dispersive vertices, kept elsewhere; with
                      // the own family, weights per lane.
                      Case{"scenes/cornell_uv.json", kShared, 0.0f, 4},
                      Case{"scenes/cornell_glossy.json", kShared, 0.0f, 4},
                      Case{"scenes/validation/mollify_mirror.json", kShared, 0.0f, 4},
                      Case{"scenes/cornell_uv.json", kBoth, 0.0f, 4},
                      Case{"scenes/cornell_uv.json", kOwn, 0.0f, 3},
                      Case{"scenes/cornell_uv.json", kOwn, 20.0f, 4},
                      Case{"scenes/validation/mollify_mirror.json", kBoth, 0.0f, 4},
                      Case{"scenes/validation/single_sphere_environment.json", kBoth, 0.0f, 4},
                      // The merged light subpath: the shared lanes fork where sampling depends on
                      // the wavelength (fluorescent, dispersive, glossy-coated vertices).
                      Case{"scenes/cornell_uv.json", kBoth, 0.0f, 1, true},
                      Case{"scenes/cornell_uv.json", kBoth, 0.0f, 4, true},
                      Case{"scenes/uv_caustic.json", kBoth, 0.0f, 4, true},
                      Case{"scenes/validation/furnace_fluorescent.json", kBoth, 0.0f, 4, true},  // a fluorescent emitter
                      Case{"scenes/validation/mollify_mirror.json", kBoth, 0.0f, 4, true},
                      Case{"scenes/validation/furnace_point_light.json", kBoth, 0.0f, 4, true},
                      Case{"scenes/validation/smooth_sphere_distant.json", kBoth, 0.0f, 4, true},
                      Case{"scenes/validation/single_sphere_environment.json", kBoth, 0.0f, 4, true},
                      // Cameras with a lens point of their own per connection, and parallel rays.
                      Case{"scenes/cornell_glossy.json", kBoth, 0.0f, 4, false, CameraKind::ThinLens},
                      Case{"scenes/cornell_glossy.json", kBoth, 0.0f, 4, true, CameraKind::Orthographic},
                      // Medium vertices (docs/media.md §5): a fluorescent, scattering medium around
                      // the camera; a fluorescent dye behind glass walls.
                      Case{"scenes/validation/media_fluorescent_furnace.json", kBoth, 0.0f},
                      Case{"scenes/validation/media_fluorescent_furnace.json", kOwn, 0.0f},
                      Case{"scenes/validation/media_fluorescent_furnace.json", kShared, 0.0f},
                      Case{"scenes/fluorescein_cuvette.json", kBoth, 0.0f},
                      // Lanes in media: they end at a flight through a medium, and a join through
                      // one serves lane 0 alone.
                      Case{"scenes/validation/media_fluorescent_furnace.json", kBoth, 0.0f, 4},
                      Case{"scenes/fluorescein_cuvette.json", kBoth, 0.0f, 4},
                      Case{"scenes/fluorescein_cuvette.json", kShared, 0.0f, 4},
                      Case{"scenes/tonic_water.json", kBoth, 0.0f, 4}),
    [](const ::testing::TestParamInfo<Case>& info) {
      std::string name = describe(info.param);
      for (char& ch : name)
        if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
      return name;
    });

}  // namespace
}  // namespace kasha::bidir
