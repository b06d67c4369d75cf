// Shading normals from OBJ vertex normals (core/shape.h): interpolation, orientation relative to
// the geometric normal, fallbacks, and the loader's handling of vn.
#include <gtest/gtest.h>

#include <fstream>

#include "core/error.h"
#include "core/rng.h"
#include "materials/lambertian.h"
#include "scene/scene_loader.h"
#include "tests/temp_dir.h"
#include "tests/support.h"

namespace kasha {
namespace {

class ShadingNormals : public test::TempDirTest {
 protected:
  ShadingNormals() : TempDirTest("shading_normals") {}

  // A scene with the OBJ text as its only shape, lit by a point light.
  std::unique_ptr<Scene> load(const std::string& obj) {
    std::ofstream(dir + "/m.obj") << obj;
    std::ofstream(dir + "/s.json") << R"({
  "camera": {"position": [0.3, 0.3, 2], "look_at": [0.3, 0.3, 0], "fov": 30, "resolution": [4, 4]},
  "materials": {"white": {"type": "lambertian", "reflectance": 0.5}},
  "shapes": [{"type": "mesh", "file": "m.obj", "material": "white"}],
  "lights": [{"type": "point", "position": [0, 0, 1], "intensity": 1}]
})";
    return loadScene(dir + "/s.json");
  }
};

// The triangle (0,0,0) (1,0,0) (0,1,0) faces +z; its corners' normals lean different ways.
const char* kTilted = "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nvn 1 0 1\nvn 0 1 1\nf 1//1 2//2 3//3\n";

TEST_F(ShadingNormals, InterpolatedAndNormalised) {
  const auto scene = load(kTilted);
  const Shape& s = scene->shapes[0];
  ASSERT_EQ(s.cornerNormals.size(), 3u);
  const Vec3 ng(0, 0, 1);
  EXPECT_EQ(s.shadingNormal(0, Vec2(0.0f), ng), ng) << "corner 0";
  const Vec3 c1 = s.shadingNormal(0, Vec2(1.0f, 0.0f), ng);
  EXPECT_NEAR(c1.x, 1.0f / std::sqrt(2.0f), 1e-6f);
  EXPECT_NEAR(c1.z, 1.0f / std::sqrt(2.0f), 1e-6f);
  // Barycentrics (0.2, 0.3) of corners 1 and 2, with the OBJ normals as written:
  // (0,0,1)·0.5 + (1,0,1)·0.2 + (0,1,1)·0.3 = (0.2, 0.3, 1.0), then normalised.
  const Vec3 n = s.shadingNormal(0, Vec2(0.2f, 0.3f), ng);
  const Vec3 expect = glm::normalize(Vec3(0.2f, 0.3f, 1.0f));
  EXPECT_NEAR(glm::length(n - expect), 0.0f, 1e-6f);
  // Through the acceleration structure, at the hit's barycentrics.
  const std::optional<Hit> h = scene->accel->intersect(Ray{Vec3(0.2f, 0.3f, 1.0f), Vec3(0, 0, -1)});
  ASSERT_TRUE(h);
  EXPECT_NEAR(glm::length(s.shadingNormal(h->prim, h->bary, h->ng) - expect), 0.0f, 1e-5f);
}

// Normals written against the winding are turned to the geometric normal's side; degenerate
// and non-finite ones fall back to the geometric normal.
TEST_F(ShadingNormals, OrientationAndFallbacks) {
  const auto flipped = load("v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 -1\nf 1//1 2//1 3//1\n");
  EXPECT_EQ(flipped->shapes[0].shadingNormal(0, Vec2(0.3f), Vec3(0, 0, 1)), Vec3(0, 0, 1));
  const auto zero = load("v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 0\nf 1//1 2//1 3//1\n");
  EXPECT_EQ(zero->shapes[0].shadingNormal(0, Vec2(0.3f), Vec3(0, 0, 1)), Vec3(0, 0, 1));
  // Opposite normals cancel half-way.
  const auto cancel = load("v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 1 0 0\nvn -1 0 0\nf 1//1 2//2 3//1\n");
  EXPECT_EQ(cancel->shapes[0].shadingNormal(0, Vec2(0.5f, 0.0f), Vec3(0, 0, 1)), Vec3(0, 0, 1));
  Shape sphere;
  sphere.kind = Shape::Kind::Sphere;
  EXPECT_EQ(sphere.shadingNormal(0, Vec2(0.0f), Vec3(0, 1, 0)), Vec3(0, 1, 0));
  const auto none = load("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  EXPECT_TRUE(none->shapes[0].cornerNormals.empty());
  EXPECT_EQ(none->shapes[0].shadingNormal(0, Vec2(0.3f), Vec3(0, 0, 1)), Vec3(0, 0, 1));
}

// Dropping a zero-area triangle keeps the normals of the others with their triangles.
TEST_F(ShadingNormals, DegenerateTrianglesKeepNormalsAligned) {
  const auto scene = load("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 2 0 0\nvn 0 0 1\nvn 1 0 1\n"
                          "f 1//1 2//1 4//1\nf 1//2 2//2 3//2\n");  // the first is degenerate
  const Shape& s = scene->shapes[0];
  ASSERT_EQ(s.indices.size(), 3u);
  const Vec3 n = s.shadingNormal(0, Vec2(0.3f), Vec3(0, 0, 1));
  EXPECT_NEAR(n.x, 1.0f / std::sqrt(2.0f), 1e-6f);
}

TEST_F(ShadingNormals, SomeFacesWithoutNormalsIsAnError) {
  try {
    load("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nvn 0 0 1\nf 1//1 2//1 3//1\nf 2 4 3\n");
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()),
              dir + "/s.json: /shapes/0/file: '" + dir + "/m.obj': some faces have vertex normals (vn) and some do not");
  }
}

// The furnace at one point, in both transport modes: a white Lambertian Bsdf whose shading normal
// is tilted by α from the geometric one. The mean path weight f·|cos θ_s|/pdf of a sampled
// direction (what the integrators multiply by) must be Veach's f_s integrated with the geometric
// cosine (materials/shading_normal.h): (1 + cos α)/2 for a camera path (Radiance: ω_i sampled),
// (ω_i·n_s)/(ω_i·n_g)·(1 + cos α)/2 for a light path arriving along ω_i (Importance: ω_o sampled).
TEST(ShadingNormalBsdf, FurnaceInBothTransportModes) {
  const Lambertian white(Spectrum::constant(1.0f));
  const float lambda = 550.0f;
  for (const float alphaDeg : {0.0f, 10.0f, 30.0f, 60.0f}) {
    const float alpha = alphaDeg * kPi / 180.0f;
    const Frame geometric = Frame::fromNormal(Vec3(0, 0, 1));
    const Frame shading = Frame::fromNormal(Vec3(std::sin(alpha), 0.0f, std::cos(alpha)));
    const Bsdf bsdf = white.bsdf(HitContext{Vec2(0.0f), geometric, shading, {&lambda, 1}});
    // A known direction on the same side of both normals, tilted towards -x.
    const Vec3 known = bsdf.toLocal(glm::normalize(Vec3(-0.3f, 0.2f, 1.0f)));
    const Vec3 ngLocal = bsdf.toLocal(geometric.n);
    for (const TransportMode mode : {TransportMode::Radiance, TransportMode::Importance}) {
      SCOPED_TRACE(std::string(toString(mode)) + ", alpha " + std::to_string(alphaDeg));
      Rng rng(17);
      const int n = 200000;
      double sum = 0.0, sum2 = 0.0;
      for (int i = 0; i < n; ++i) {
        const std::optional<ScatterSample> s = bsdf.sample(mode, known, lambda, Vec3(rng.uniform(), rng.uniform(), rng.uniform()));
        const double w = s ? double(s->f * std::abs(s->w.z) / s->pdf) : 0.0;
        sum += w, sum2 += w * w;
      }
      const double mean = sum / n, se = std::sqrt(std::max(0.0, sum2 / n - mean * mean) / n);
      double exact = 0.5 * (1.0 + std::cos(double(alpha)));
      if (mode == TransportMode::Importance) exact *= double(known.z) / double(glm::dot(known, ngLocal));
      EXPECT_NEAR(mean, exact, 4.0 * se + 1e-6) << "mean " << mean << " ± " << se;
      if (alphaDeg >= 10.0f) EXPECT_GT(std::abs(mean - 1.0), 8.0 * se) << "the tilt is visible";
    }
  }
}

}  // namespace
}  // namespace kasha
