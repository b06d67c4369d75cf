// The equirectangular environment light (core/envmap_light.h): Mitsuba's direction ↔ image
// mapping at hand-computed points, χ² test of its direction sampling against its own pdf, the
// same density from sampleLi, sampleEmission and emissionPdfs, a furnace-style closed form (a
// constant map around a convex Lambertian sphere: the sphere is ρ·L, and L has the map's colour),
// equality with the uniform environment light of the same spectrum, and path tracing, light
// tracing and BDPT agreeing under a non-constant map.
#include <gtest/gtest.h>
#include <unistd.h>

#include <ImfRgbaFile.h>
#include <glm/gtc/matrix_transform.hpp>

#include <cmath>
#include <filesystem>
#include <functional>

#include "core/color.h"
#include "core/envmap_light.h"
#include "core/error.h"
#include "core/rng.h"
#include "integrators/integrator_factory.h"
#include "scene/scene_loader.h"
#include "tests/region_batches.h"
#include "tests/support.h"

namespace kasha {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

RgbImage image(int w, int h, const std::function<Vec3(int, int)>& f) {
  RgbImage img{w, h, {}};
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) img.pixels.push_back(f(x, y));
  return img;
}

// A map with structure: a gradient, a dark band and a bright spot.
Vec3 patterned(int x, int y) {
  if (x == 5 && y == 2) return Vec3(40.0f, 30.0f, 10.0f);
  if (y == 5) return Vec3(0.0f);
  return Vec3(0.2f + 0.05f * float(x), 0.3f, 0.1f + 0.1f * float(y));
}

const SceneBounds kBounds{Vec3(0.0f), 2.0f};
const WavelengthRange kRange{360.0f, 830.0f};

glm::mat4 rotation() { return glm::rotate(glm::mat4(1.0f), 0.7f, glm::normalize(Vec3(1, 2, 0.5f))); }

TEST(EnvMapLight, MitsubaMappingAtHandComputedPoints) {
  const EnvMapLight l(image(8, 4, [](int, int) { return Vec3(1.0f); }), glm::mat4(1.0f), 1.0f, kBounds, kRange);
  // u = atan2(d_x, −d_z)/2π, v = acos(d_y)/π.
  const auto expectUv = [&](Vec3 d, Vec2 uv) {
    const Vec2 got = l.directionToUv(d);
    EXPECT_NEAR(got.x, uv.x, 1e-6f) << d.x << " " << d.y << " " << d.z;
    EXPECT_NEAR(got.y, uv.y, 1e-6f);
  };
  expectUv(Vec3(0, 0, -1), Vec2(0.0f, 0.5f));
  expectUv(Vec3(1, 0, 0), Vec2(0.25f, 0.5f));
  expectUv(Vec3(0, 0, 1), Vec2(0.5f, 0.5f));
  expectUv(Vec3(-1, 0, 0), Vec2(0.75f, 0.5f));
  expectUv(glm::normalize(Vec3(0, 1, -1)), Vec2(0.0f, 0.25f));
  for (const Vec2 uv : {Vec2(0.1f, 0.2f), Vec2(0.6f, 0.9f), Vec2(0.95f, 0.5f)}) {
    const Vec2 back = l.directionToUv(l.uvToDirection(uv));
    EXPECT_NEAR(back.x, uv.x, 1e-5f);
    EXPECT_NEAR(back.y, uv.y, 1e-5f);
  }
  // A rotation moves the map with it: 90° about +y takes local +x to world −z.
  const EnvMapLight r(image(8, 4, [](int, int) { return Vec3(1.0f); }),
                      glm::rotate(glm::mat4(1.0f), kPi / 2.0f, Vec3(0, 1, 0)), 1.0f, kBounds, kRange);
  const Vec2 uv = r.directionToUv(Vec3(0, 0, -1));
  EXPECT_NEAR(uv.x, 0.25f, 1e-6f);
  EXPECT_NEAR(uv.y, 0.5f, 1e-6f);
}

TEST(EnvMapLight, RadianceIsTheTexelsColour) {
  // The bright texel (5, 2) is seen in its direction, with its colour (rgb_illuminant: the film's
  // linear sRGB of L is the texel's RGB).
  const EnvMapLight l(image(8, 6, patterned), rotation(), 2.0f, kBounds, kRange);
  const Vec3 w = l.uvToDirection(Vec2(5.5f / 8.0f, 2.5f / 6.0f));
  Vec3 xyz(0.0f);
  for (float nm = 360.0f; nm <= 830.0f; nm += 0.5f) xyz += Observer::cie1931().weight(nm) * l.Le(nm, w) * 0.5f;
  const Vec3 rgb = xyzToLinearSrgb(xyz) / 2.0f;
  EXPECT_NEAR(rgb.x, 40.0f, 0.4f);
  EXPECT_NEAR(rgb.y, 30.0f, 0.3f);
  EXPECT_NEAR(rgb.z, 10.0f, 0.2f);
}

// Expected fraction of sampled directions in each (cos θ, φ) bin of the world sphere: ∫ pdf dω
// by the midpoint rule on 32 × 32 points per bin.
std::vector<double> expectedBins(const EnvMapLight& l, int nz, int nphi, int sub) {
  std::vector<double> e(size_t(nz * nphi), 0.0);
  const double cell = (2.0 / nz) * (2.0 * M_PI / nphi) / double(sub * sub);
  for (int i = 0; i < nz; ++i)
    for (int j = 0; j < nphi; ++j)
      for (int a = 0; a < sub; ++a)
        for (int b = 0; b < sub; ++b) {
          const double z = -1.0 + (i + (a + 0.5) / sub) * 2.0 / nz, phi = (j + (b + 0.5) / sub) * 2.0 * M_PI / nphi;
          const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
          e[size_t(i * nphi + j)] += l.pdfDirection(Vec3(float(r * std::cos(phi)), float(r * std::sin(phi)), float(z))) * cell;
        }
  return e;
}

TEST(EnvMapLight, SamplingMatchesItsPdfChi2) {
  const EnvMapLight l(image(16, 8, [](int x, int y) { return patterned(x % 8, y % 6); }), rotation(), 1.0f, kBounds, kRange);
  constexpr int kNz = 12, kNphi = 24, kSamples = 400000;
  std::vector<double> expected = expectedBins(l, kNz, kNphi, 32);
  double total = 0.0;
  for (double v : expected) total += v;
  EXPECT_NEAR(total, 1.0, 2e-3);  // the pdf integrates to 1 over the sphere
  std::vector<double> observed(expected.size(), 0.0);
  Rng rng(7, 0);
  for (int s = 0; s < kSamples; ++s) {
    const auto [w, pdf] = l.sampleDirection(Vec2(rng.uniform(), rng.uniform()));
    ASSERT_GT(pdf, 0.0f);
    const int i = std::clamp(int((w.z + 1.0f) * 0.5f * kNz), 0, kNz - 1);
    float phi = std::atan2(w.y, w.x);
    if (phi < 0.0f) phi += 2.0f * kPi;
    const int j = std::clamp(int(phi / (2.0f * kPi) * kNphi), 0, kNphi - 1);
    observed[size_t(i * kNphi + j)] += 1.0;
  }
  for (double& e : expected) e *= kSamples;
  EXPECT_GT(test::chi2PValue(observed, expected), 1e-3);
}

TEST(EnvMapLight, LightAndEmissionSamplesShareTheDensity) {
  const EnvMapLight l(image(8, 6, patterned), rotation(), 1.5f, kBounds, kRange);
  Rng rng(3, 0);
  for (int s = 0; s < 200; ++s) {
    const Vec2 u(rng.uniform(), rng.uniform()), u2(rng.uniform(), rng.uniform());
    const auto ls = l.sampleLi(Vec3(0.3f, 0.1f, 0.0f), 550.0f, u);
    ASSERT_TRUE(ls);
    EXPECT_FLOAT_EQ(ls->pdf, l.pdfDirection(ls->wi));
    EXPECT_FLOAT_EQ(ls->Li, l.Le(550.0f, ls->wi));
    const auto es = l.sampleEmission(550.0f, u2, u);
    ASSERT_TRUE(es);
    EXPECT_NEAR(glm::dot(es->w, -ls->wi), 1.0f, 1e-6f);  // the same direction, travelling inwards
    float pdfPos = 0.0f, pdfDir = 0.0f;
    l.emissionPdfs(es->p, Vec3(0.0f), es->w, pdfPos, pdfDir);
    EXPECT_FLOAT_EQ(pdfDir, es->pdfDir);
    EXPECT_FLOAT_EQ(pdfPos, es->pdfPos);
    EXPECT_FLOAT_EQ(es->pdfDir, ls->pdf);
  }
}

// ---- renders ---------------------------------------------------------------------------------

class EnvMapScene : public ::testing::Test {
 protected:
  void SetUp() override {
    dir = fs::path(::testing::TempDir()) / ("kasha_envmap." + std::to_string(getpid()));
    fs::create_directories(dir);
  }
  void TearDown() override {
    if (!HasFailure()) fs::remove_all(dir);
  }
  std::string writeExr(const std::string& name, int w, int h, const std::function<Vec3(int, int)>& f) const {
    std::vector<Imf::Rgba> px;
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        const Vec3 c = f(x, y);
        px.emplace_back(c.x, c.y, c.z, 1.0f);
      }
    const std::string path = (dir / name).string();
    Imf::RgbaOutputFile out(path.c_str(), w, h, Imf::WRITE_RGBA);
    out.setFrameBuffer(px.data(), 1, size_t(w));
    out.writePixels(h);
    return path;
  }
  // A Lambertian sphere (reflectance 0.5) seen in an 8 × 8 view, optionally on a floor, lit by
  // `light`. Without the floor every pixel sees the sphere (its silhouette is 19.5° off the axis,
  // the view's corners 18.1° at fov 26): light tracing cannot see the environment itself.
  std::unique_ptr<Scene> sphere(const json& light, bool floor) const {
    json j = {{"render", {{"max_depth", 64}}},
              {"camera", {{"position", {0, 0, -3}}, {"look_at", {0, 0, 0}}, {"fov", floor ? 60 : 26}, {"resolution", {8, 8}}}},
              {"materials", {{"grey", {{"type", "lambertian"}, {"reflectance", 0.5}}}}},
              {"shapes", {{{"type", "sphere"}, {"center", {0, 0, 0}}, {"radius", 1}, {"material", "grey"}}}},
              {"lights", {light}}};
    if (floor)
      j["shapes"].push_back({{"type", "rectangle"}, {"center", {0, -1, 0}}, {"u", {3, 0, 0}}, {"v", {0, 0, 3}}, {"material", "grey"}});
    return loadSceneFromJson(j, (dir / "scene.json").string());
  }
  fs::path dir;
};

// 32 batches; light tracing, whose paths mostly miss the small view, takes 8 times the samples.
std::vector<test::BatchStats> renderRegions(const Scene& scene, const std::string& integrator, int regions, uint64_t seed) {
  const std::unique_ptr<Integrator> in = makeIntegrator(integrator, scene, scene.render);
  const int grid = regions == 1 ? 1 : 2;
  return test::regionBatches(scene, *in, 8, 8, regions, [grid](int x, int y) { return (y * grid / 8) * grid + x * grid / 8; },
                             integrator == "lt" ? 32 : 4, 32, seed);
}

// A constant map of colour (c, c, c) around a convex Lambertian sphere: every pixel sees the
// sphere, whose radiance is ρ·L (it never sees itself), and L's colour is (c, c, c).
TEST_F(EnvMapScene, ConstantMapFurnaceClosedForm) {
  constexpr float c = 0.4f;
  const std::string map = writeExr("grey.exr", 8, 4, [](int, int) { return Vec3(c); });
  const auto scene = sphere({{"type", "envmap"}, {"file", map}, {"scale", 1.0}}, false);
  const RgbIlluminant L = rgbIlluminant(Vec3(c));
  Vec3 xyzL(0.0f);
  for (float nm = 360.0f; nm <= 830.0f; nm += 0.5f) xyzL += Observer::cie1931().weight(nm) * L(nm) * 0.5f;
  const Vec3 rgb = xyzToLinearSrgb(xyzL);
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(rgb[k], c, 0.01f);
  for (const char* integrator : {"pt", "lt", "bdpt-independent"}) {
    const auto stats = renderRegions(*scene, integrator, 1, 11);
    for (int k = 0; k < 3; ++k) {
      const double expected = 0.5 * xyzL[k] * 64.0;  // summed over the 64 pixels
      EXPECT_NEAR(stats[size_t(k)].mean, expected, 4.0 * stats[size_t(k)].stderr_) << integrator << " channel " << k;
    }
  }
}

// The same constant map and the uniform environment light with the map's spectrum render the
// same image of a sphere on a floor (their densities differ: piecewise ∝ sin θ vs uniform).
TEST_F(EnvMapScene, ConstantMapEqualsUniformEnvironment) {
  constexpr float c = 0.7f;
  const std::string map = writeExr("grey.exr", 16, 8, [](int, int) { return Vec3(c); });
  const RgbIlluminant L = rgbIlluminant(Vec3(c));
  json wl = json::array(), v = json::array();
  for (int nm = 360; nm <= 830; ++nm) {
    wl.push_back(nm);
    v.push_back(L(float(nm)));
  }
  const auto a = sphere({{"type", "envmap"}, {"file", map}}, true);
  const auto b = sphere({{"type", "environment"}, {"radiance", {{"type", "tabulated"}, {"wavelengths", wl}, {"values", v}}}}, true);
  for (const char* integrator : {"pt", "bdpt-independent"}) {
    const auto sa = renderRegions(*a, integrator, 4, 5), sb = renderRegions(*b, integrator, 4, 1000);
    for (size_t i = 0; i < sa.size(); ++i)
      EXPECT_NEAR(sa[i].mean, sb[i].mean, 4.0 * std::hypot(sa[i].stderr_, sb[i].stderr_)) << integrator << " " << i;
  }
}

// Under a map with a bright spot, path tracing (NEE + MIS), light tracing (emission sampling)
// and BDPT (all strategies) agree on the sphere.
TEST_F(EnvMapScene, IntegratorsAgreeUnderAPatternedMap) {
  const std::string map = writeExr("pattern.exr", 8, 6, patterned);
  const auto scene = sphere({{"type", "envmap"}, {"file", map}, {"transform", {{1, 0, 0, 0}, {0, 0, -1, 0}, {0, 1, 0, 0}, {0, 0, 0, 1}}}}, false);
  const auto pt = renderRegions(*scene, "pt", 4, 21);
  for (const char* integrator : {"lt", "bdpt-independent"}) {
    const auto other = renderRegions(*scene, integrator, 4, 77);
    for (size_t i = 0; i < pt.size(); ++i)
      EXPECT_NEAR(pt[i].mean, other[i].mean, 4.0 * std::hypot(pt[i].stderr_, other[i].stderr_)) << integrator << " " << i;
  }
}

TEST_F(EnvMapScene, BadImagesAreErrors) {
  const std::string black = writeExr("black.exr", 4, 2, [](int, int) { return Vec3(0.0f); });
  EXPECT_THROW(sphere({{"type", "envmap"}, {"file", black}}, false), InputError);
  const std::string negative = writeExr("neg.exr", 4, 2, [](int x, int) { return Vec3(x == 1 ? -1.0f : 1.0f); });
  try {
    sphere({{"type", "envmap"}, {"file", negative}}, false);
    FAIL() << "loaded a negative map";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("pixel (1, 0) is negative"), std::string::npos) << e.what();
  }
  EXPECT_THROW(sphere({{"type", "envmap"}, {"file", (dir / "missing.exr").string()}}, false), InputError);
  const std::string ok = writeExr("ok.exr", 4, 2, [](int, int) { return Vec3(1.0f); });
  EXPECT_THROW(sphere({{"type", "envmap"}, {"file", ok}, {"transform", {{2, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 1, 0}, {0, 0, 0, 1}}}}, false),
               InputError);  // not a rotation
}

}  // namespace
}  // namespace kasha
