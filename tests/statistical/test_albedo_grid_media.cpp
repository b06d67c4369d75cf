// A homogeneous medium with a spatially varying albedo (docs/media.md §7) against an independent
// computation of the same scene: one medium whose albedo grid repeats along x (16 × 1 × 1 cells,
// `repeat`, over a period of 4 units: 4 blue, 8 red, 4 blue) fills three spheres of radius 0.85
// placed where the trilinear lookup reads one colour only (x = 0: among the red cells; x = 2: the
// last blue cells and, wrapped, the first; x = −2: the first and, wrapped backwards, the last).
// The same spheres filled with two ordinary homogeneous media, σ_s = σ_t·α(λ) and σ_a = σ_t·(1 − α)
// given as spectra (α the colours' Jakob–Hanika upsampling, tabulated every nanometre here),
// render the same image in expectation. σ_t depends on λ, so the lanes see different albedos and
// extinctions. pt with 4 lanes on the two-media scene is the reference; pt with 4 lanes and with
// one, lt, bdpt and vcm on the grid must agree within 4σ per region, and ppm with ppm on the two
// media (the same blur of the same radiance).
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "core/rgb_spectrum.h"
#include "integrators/integrator_factory.h"
#include "scene/scene_loader.h"
#include "tests/integrator_names.h"
#include "tests/region_batches.h"
#include "tests/temp_dir.h"
#include "tests/volume_grid_files.h"

namespace kasha {
namespace {

constexpr int kWidth = 24, kHeight = 8, kRegions = 6;
const Vec3 kRed(0.95f, 0.6f, 0.2f), kBlue(0.15f, 0.5f, 0.9f);

float sigmaT(float lambda) { return 3.0f - 1.5f * (lambda - 400.0f) / 300.0f; }  // 3 at 400 nm, 1.5 at 700

// A tabulated spectrum, every nanometre over 400–700, of f(λ).
template <class F>
std::string tabulated(F f) {
  std::string wavelengths, values;
  for (int l = 400; l <= 700; ++l) {
    wavelengths += (l > 400 ? ", " : "") + std::to_string(l);
    values += (l > 400 ? ", " : "") + std::to_string(f(float(l)));
  }
  return R"({"type": "tabulated", "wavelengths": [)" + wavelengths + R"(], "values": [)" + values + "]}";
}

// The homogeneous medium of albedo `colour`: σ_s = σ_t·α, σ_a = σ_t·(1 − α).
std::string plainMedium(const Vec3& colour) {
  const RgbSigmoid albedo = rgbToSigmoid(colour);
  return R"({"type": "homogeneous", "g": 0.5, "sigma_s": )" + tabulated([&](float l) { return sigmaT(l) * albedo(l); }) +
         R"(, "sigma_a": )" + tabulated([&](float l) { return sigmaT(l) * (1.0f - albedo(l)); }) + "}";
}

class AlbedoGridMedia : public test::TempDirTest {
 protected:
  AlbedoGridMedia() : TempDirTest("albedo_grid_media") {}

  // Three spheres of radius 0.85 at x = −2, 0, 2 over a white floor, under a long lamp: filled
  // with the one gridded medium (`grid`), or with blue, red, blue ordinary media.
  std::unique_ptr<Scene> scene(bool grid) {
    std::vector<float> cells;
    for (int i = 0; i < 16; ++i) {
      const Vec3& c = i >= 4 && i < 12 ? kRed : kBlue;
      cells.insert(cells.end(), {c.x, c.y, c.z});
    }
    writeFile("albedo.vol", test::volBytes({16, 1, 1}, 3, cells));
    // The grid's unit cube spans x from −2 to 2: u = (x + 2)/4. Red alone where the stencil's
    // cells are 4..11, u in [4.5, 11.5]/16, x in [−0.875, 0.875]; blue alone for cells 12..15, 0..3
    // (wrapped), x within 0.875 of ±2.
    const std::string media =
        grid ? R"("fog": {"type": "homogeneous", "g": 0.5, "sigma_t": )" + tabulated(sigmaT) +
                   R"(, "albedo_grid": {"file": "albedo.vol", "wrap_mode": "repeat",
                        "transform": [[4, 0, 0, -2], [0, 4, 0, 0], [0, 0, 4, 0], [0, 0, 0, 1]]}})"
             : R"("blue": )" + plainMedium(kBlue) + R"(, "red": )" + plainMedium(kRed);
    const auto sphere = [&](float x, const char* medium) {
      return R"({"type": "sphere", "center": [)" + std::to_string(x) + R"(, 0, 0], "radius": 0.85, "interior": ")" +
             (grid ? "fog" : medium) + R"("})";
    };
    return loadSceneFromString(R"({
      "wavelength_range": [400, 700],
      "render": {"spp": 1, "max_depth": 10},
      "camera": {"position": [0, 0.8, -7], "look_at": [0, 0, 0], "fov": 20, "resolution": [24, 8]},
      "materials": {"white": {"type": "lambertian", "reflectance": 0.7}},
      "media": {)" + media + R"(},
      "shapes": [{"type": "rectangle", "center": [0, -0.9, 0], "u": [0, 0, 4], "v": [8, 0, 0], "material": "white"},
                 {"type": "rectangle", "center": [0, 2.5, -0.5], "u": [6, 0, 0], "v": [0, 0, 2], "material": "white",
                  "emission": {"radiance": 2, "two_sided": true}},
                 )" + sphere(-2.0f, "blue") + ", " + sphere(0.0f, "red") + ", " + sphere(2.0f, "blue") + R"(]
    })", dir + (grid ? "/grid.json" : "/plain.json"));
  }

  static std::vector<test::BatchStats> regions(const Scene& s, const std::string& name, int lanes, int spp,
                                              const PhotonMappingSettings& ppm = {}) {
    RenderSettings settings = s.render;
    settings.heroWavelengths = lanes;
    settings.ppm = ppm;
    const auto integrator = test::makeTestIntegrator(name, s, settings);
    // A third of the image's width (a sphere each) by halves of its height.
    const auto region = [](int x, int y) { return (x * 3 / kWidth) * 2 + y * 2 / kHeight; };
    return test::regionBatches(s, *integrator, kWidth, kHeight, kRegions, region, spp, 12, 7);
  }
};

TEST_F(AlbedoGridMedia, GridAgreesWithTwoHomogeneousMedia) {
  const auto plain = scene(false), gridded = scene(true);
  ASSERT_TRUE(gridded->media[0]->spatiallyVaryingAlbedo());
  const std::vector<test::BatchStats> reference = regions(*plain, "pt", 4, 64);
  // Each integrator on the grid against the reference; power: a combined standard error below 6%
  // of a region, or 2% of the brightest.
  const auto agrees = [&](const std::string& name, int lanes, int spp) {
    SCOPED_TRACE(name + " with " + std::to_string(lanes) + " lanes");
    test::expectRegionsAgree(reference, regions(*gridded, name, lanes, spp), 4.0, 0.06, 0.02);
  };
  agrees("pt", 4, 64);
  agrees("pt", 1, 96);
  agrees("lt", 4, 64);
  agrees("bdpt", 1, 64);
  agrees("vcm", 1, 64);
}

// ppm's volume photons, stored and gathered in the gridded medium, against ppm on the two media.
TEST_F(AlbedoGridMedia, VolumePhotonsAgreeWithTwoHomogeneousMedia) {
  PhotonMappingSettings ppm;
  ppm.photonsPerPass = 8192;
  ppm.radius = 0.1f;
  ppm.volumeRadius = 0.2f;
  // Power: a combined standard error below 6% of a region, or 2% of the brightest.
  test::expectRegionsAgree(regions(*scene(false), "ppm", 4, 32, ppm), regions(*scene(true), "ppm", 4, 32, ppm), 4.0,
                           0.06, 0.02);
}

}  // namespace
}  // namespace kasha
