// Wavelength lanes through media in the bidirectional engine (docs/media.md §5): joins whose segment
// runs through a medium between ends that several lanes reach. A diffuse floor in air and a slab of
// an absorbing medium whose σ_a rises steeply over the visible range (index-matched, no scattering),
// seen straight down by an orthographic camera; the floor's radiance has a closed form.
//   - Light above the slab, camera under it: next-event estimation from the floor (every lane)
//     crosses the slab. L = ρ/π · E_0(λ) · e^{−σ_a(λ)·d} (a distant light at normal incidence).
//   - Light under the slab, camera above it: the camera connection of a light subpath's floor
//     vertex (every lane) crosses the slab. The image's mean is ρ/π · I(λ) · ḡ · e^{−σ_a(λ)·d}, ḡ the
//     mean over the footprint of the irradiance per unit intensity (tests/point_lit_plane.h).
// Each join must count one lane, at its own wavelength: with every lane given lane 0's
// transmittance the floor's colour shifts, by hundreds of σ in the first test and in the second
// (where the camera paths, which are right, share the weight) by 4–6σ at 16 samples per pixel: it
// takes 64, where X shifts by 13σ.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>

#include <nlohmann/json.hpp>

#include "materials/lambertian.h"
#include "tests/closed_form_support.h"

namespace kasha {
namespace {

using namespace test;
using nlohmann::json;

constexpr double kThickness = 0.2;  // the slab, y in [0.5, 0.7]

// The floor (y = 0, ρ = 0.7), the slab and the camera above (y = 1) or under (y = 0.3) the slab,
// looking straight down at a footprint 2a × 2a.
json slabScene(bool cameraAbove, const json& light, double a) {
  return {
      {"render", {{"spp", 16}, {"max_depth", 4}, {"rr_depth", 8}, {"seed", 3}}},
      {"camera",
       {{"type", "orthographic"},
        {"position", {0.0, cameraAbove ? 1.0 : 0.3, 0.0}},
        {"look_at", {0.0, 0.0, 0.0}},
        {"up", {0, 0, 1}},
        {"extent", {2.0 * a, 2.0 * a}},
        {"resolution", {8, 8}}}},
      {"media",
       {{"dye",
         {{"type", "homogeneous"},
          {"sigma_a", {{"type", "tabulated"}, {"wavelengths", {360, 450, 550, 650, 830}}, {"values", {0.5, 1, 6, 12, 12}}}},
          {"sigma_s", 0}}}}},
      {"materials", {{"floor", {{"type", "lambertian"}, {"reflectance", 0.7}}}}},
      {"shapes",
       {{{"name", "floor"}, {"type", "rectangle"}, {"center", {0, 0, 0}}, {"u", {20, 0, 0}}, {"v", {0, 0, 20}},
         {"material", "floor"}},
        {{"name", "slab"},
         {"type", "mesh"},
         {"file", "unit_cube.obj"},
         {"interior", "dye"},
         {"transform", {{40, 0, 0, 0}, {0, kThickness, 0, 0.6}, {0, 0, 40, 0}, {0, 0, 0, 1}}}}}},
      {"lights", {light}}};
}

std::unique_ptr<Scene> load(const json& j) { return loadSceneFromJson(j, sourcePath("scenes/validation/media_slab.json")); }

// ρ/π · S(λ) · e^{−σ_a(λ)·d} over λ, times `scale`, in XYZ.
Vec3 attenuatedFloorXyz(const Scene& scene, const std::function<double(double)>& source, double scale) {
  const Medium& m = *scene.media.at(0);
  const double rho = dynamic_cast<const Lambertian&>(*scene.materials.at(0)).reflectance()(550.0f);
  const Grid g(scene.range);
  return toXyz(g, g.sample([&](double l) {
    return scale * rho / kPi * source(l) * std::exp(-double(m.sigmaT(float(l))) * kThickness);
  }));
}

class MediaLanes : public ::testing::TestWithParam<const char*> {
 protected:
  void expectAgreement(Scene& scene, const Vec3& exact, int spp) const {
    RenderSettings settings = scene.render;
    settings.heroWavelengths = 4;
    expectXyzAgreement(scene, GetParam(), settings, exact, 16, spp);
  }
};

TEST_P(MediaLanes, NextEventEstimationThroughASlab) {
  const json light = {{"type", "distant"},
                      {"direction", {0, -1, 0}},
                      {"irradiance", {{"type", "tabulated"}, {"wavelengths", {360, 830}}, {"values", {2, 2}}}}};
  auto scene = load(slabScene(false, light, 0.5));
  const auto& sun = dynamic_cast<const DistantLight&>(*scene->lights.at(0));
  expectAgreement(*scene, attenuatedFloorXyz(*scene, [&](double l) { return double(sun.irradiance(float(l))); }, 1.0), 16);
}

TEST_P(MediaLanes, CameraConnectionThroughASlab) {
  constexpr double h = 0.4, a = 0.3;  // the light's height, the footprint's half-width
  const json light = {{"type", "point"},
                      {"position", {0, h, 0}},
                      {"intensity", {{"type", "tabulated"}, {"wavelengths", {360, 830}}, {"values", {1, 1}}}}};
  auto scene = load(slabScene(true, light, a));
  const auto& lamp = dynamic_cast<const PointLight&>(*scene->lights.at(0));
  // ḡ = ∫ h/(h² + x² + z²)^{3/2} dx dz / (2a)² (tests/point_lit_plane.h).
  const double meanG = std::atan(a * a / (h * std::sqrt(h * h + 2.0 * a * a))) / (a * a);
  expectAgreement(*scene, attenuatedFloorXyz(*scene, [&](double l) { return double(lamp.intensity(float(l))); }, meanG),
                  64);
}

INSTANTIATE_TEST_SUITE_P(Bidirectional, MediaLanes, ::testing::Values("bdpt", "bdpt-shared", "bdpt-independent", "vc"),
                         [](const ::testing::TestParamInfo<const char*>& info) {
                           std::string name = info.param;
                           std::replace(name.begin(), name.end(), '-', '_');
                           return name;
                         });

}  // namespace
}  // namespace kasha
