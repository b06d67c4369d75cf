// The analytic open cylinder (core/cylinder.h) through the scene loader and Embree: ray hits
// against the textbook intersection of a ray with a tube, computed here in the cylinder's own
// coordinates (distances, points, normals, the open ends, rays from inside), occlusion, uv at
// known points, flipped normals, uniform area sampling (density, points on the surface, a χ² test
// over (φ, z) cells), and the placement from JSON and Mitsuba XML with its errors.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "core/error.h"
#include "core/rng.h"
#include "scene/mitsuba/mitsuba_scene.h"
#include "scene/scene_loader.h"
#include "tests/expect_contains.h"

namespace kasha {
namespace {

// A scene holding the JSON shape `shape` (material "m") and a point light.
std::unique_ptr<Scene> load(const std::string& shape) {
  return loadSceneFromString(R"({
  "camera": {"position": [0, -5, 0], "look_at": [0, 0, 0], "up": [0, 0, 1], "fov": 30, "resolution": [4, 4]},
  "materials": {"m": {"type": "lambertian", "reflectance": 0.5}},
  "shapes": [)" + shape + R"(],
  "lights": [{"type": "point", "position": [0, -3, 0], "intensity": 1}]
})",
                             "cylinder.json");
}

std::string loadError(const std::string& shape) {
  try {
    load(shape);
  } catch (const InputError& e) {
    return e.what();
  }
  ADD_FAILURE() << "loaded " << shape;
  return "";
}

// The tilted test cylinder: axis along (1, 2, 2)/3 from p0 = (0.5, −0.25, 0.1), length 1.5, radius
// 0.4, and its coordinates: an orthonormal frame built here by Gram–Schmidt from the axis.
const Vec3 kP0(0.5f, -0.25f, 0.1f), kAxis = Vec3(1, 2, 2) / 3.0f;
constexpr float kLength = 1.5f, kRadius = 0.4f;
const char* kTilted = R"({"type": "cylinder", "p0": [0.5, -0.25, 0.1], "p1": [1.0, 0.75, 1.1], "radius": 0.4, "material": "m"})";

struct Local {
  glm::dvec3 e1, e2, a;
  Local() : a(glm::dvec3(kAxis)) {
    e1 = glm::normalize(glm::dvec3(1, 0, 0) - a.x * a);
    e2 = glm::cross(a, e1);
  }
  glm::dvec3 of(const glm::dvec3& v) const { return {glm::dot(v, e1), glm::dot(v, e2), glm::dot(v, a)}; }
};

// The textbook answer: the smallest t > 0 with (o + t·d) at distance r from the axis and its axial
// coordinate in [0, L]; −1 if none.
double expectedT(const Vec3& o, const Vec3& d) {
  const Local f;
  const glm::dvec3 lo = f.of(glm::dvec3(o) - glm::dvec3(kP0)), ld = f.of(glm::dvec3(d));
  const double a = ld.x * ld.x + ld.y * ld.y, b = lo.x * ld.x + lo.y * ld.y, c = lo.x * lo.x + lo.y * lo.y - double(kRadius) * kRadius;
  const double disc = b * b - a * c;
  if (a == 0.0 || disc < 0.0) return -1.0;
  for (const double t : {(-b - std::sqrt(disc)) / a, (-b + std::sqrt(disc)) / a}) {
    const double z = lo.z + t * ld.z;
    if (t > 1e-9 && z >= 0.0 && z <= kLength) return t;
  }
  return -1.0;
}

TEST(Cylinder, HitsMatchTheAnalyticIntersection) {
  const auto scene = load(kTilted);
  ASSERT_EQ(scene->shapes[0].kind, Shape::Kind::Cylinder);
  EXPECT_NEAR(scene->shapes[0].area, 2.0f * kPi * kRadius * kLength, 1e-5f);
  const Local f;
  Rng rng(7);
  int hits = 0, inside = 0;
  for (int i = 0; i < 4000; ++i) {
    // Origins in a box around the cylinder (some inside the tube), directions uniform.
    const Vec3 o = kP0 + kAxis * (2.5f * rng.uniform() - 0.5f) + Vec3(rng.uniform() - 0.5f, rng.uniform() - 0.5f, rng.uniform() - 0.5f) * 1.6f;
    const float z = 1.0f - 2.0f * rng.uniform(), phi = 2.0f * kPi * rng.uniform();
    const Vec3 d(std::sqrt(1.0f - z * z) * std::cos(phi), std::sqrt(1.0f - z * z) * std::sin(phi), z);
    const double t = expectedT(o, d);
    const std::optional<Hit> h = scene->accel->intersect(Ray{o, d});
    ASSERT_EQ(h.has_value(), t > 0.0) << i << ": expected t " << t;
    if (!h) continue;
    ++hits;
    EXPECT_NEAR(h->t, t, 1e-5 * (1.0 + t)) << i;
    const glm::dvec3 p = f.of(glm::dvec3(h->p) - glm::dvec3(kP0));
    EXPECT_NEAR(std::hypot(p.x, p.y), kRadius, 1e-5) << i;
    // Outward normal: the radial direction, wherever the ray came from.
    const glm::dvec3 radial = glm::dvec3(h->p) - glm::dvec3(kP0) - p.z * f.a;
    EXPECT_NEAR(glm::length(glm::dvec3(h->ng) - radial / double(kRadius)), 0.0, 1e-5) << i;
    if (glm::dot(h->ng, d) > 0.0f) ++inside;  // hit from inside the tube
  }
  EXPECT_GT(hits, 800);
  EXPECT_GT(inside, 100);
}

TEST(Cylinder, OpenEndsOcclusionAndRayOffsets) {
  const auto scene = load(R"({"type": "cylinder", "p0": [0, 0, 0], "p1": [0, 0, 2], "radius": 0.5, "material": "m"})");
  const Accel& accel = *scene->accel;
  // Along the axis through both open ends: nothing.
  EXPECT_FALSE(accel.intersect(Ray{Vec3(0, 0, -1), Vec3(0, 0, 1)}));
  EXPECT_FALSE(accel.occluded(Vec3(0, 0, -1), Vec3(0, 0, 1), 10.0f));
  // In through the top opening, onto the inside of the wall at x = 0.5 (z ≈ 1.22).
  const Vec3 d = glm::normalize(Vec3(std::sin(0.5f), 0, -std::cos(0.5f)));
  const std::optional<Hit> in = accel.intersect(Ray{Vec3(-0.2f, 0, 2.5f), d});
  ASSERT_TRUE(in);
  EXPECT_NEAR(in->p.x, 0.5f, 1e-5f);
  EXPECT_NEAR(in->ng.x, 1.0f, 1e-6f);  // outward: the ray meets the wall's back
  // Across the tube: occluded only if the segment reaches the wall.
  EXPECT_TRUE(accel.occluded(Vec3(-2, 0, 1), Vec3(1, 0, 0), 2.0f));
  EXPECT_FALSE(accel.occluded(Vec3(-2, 0, 1), Vec3(1, 0, 0), 1.4f));
  // A ray leaving the surface from the offset point does not hit its own surface again.
  const std::optional<Hit> wall = accel.intersect(Ray{Vec3(-2, 0, 1), Vec3(1, 0, 0)});
  ASSERT_TRUE(wall);
  EXPECT_NEAR(wall->p.x, -0.5f, 1e-6f);
  for (const Vec3 out : {Vec3(-1, 0, 0), glm::normalize(Vec3(-0.01f, 1, 0)), glm::normalize(Vec3(-1, 0.2f, 0.1f))})
    EXPECT_FALSE(accel.intersect(Ray{offsetPoint(wall->p, wall->ng, out), out})) << out.y;
  // Into the tube: the far wall, not this one.
  const Vec3 across = glm::normalize(Vec3(1, 0.2f, 0.1f));
  const std::optional<Hit> far = accel.intersect(Ray{offsetPoint(wall->p, wall->ng, across), across});
  ASSERT_TRUE(far);
  EXPECT_GT(far->t, 0.9f);
}

TEST(Cylinder, UvAndFlippedNormals) {
  // Axis +z: Mitsuba's frame around it has φ = 0 along +x and φ = π/2 along +y.
  const char* shape = R"({"type": "cylinder", "p0": [0, 0, 0], "p1": [0, 0, 2], "radius": 0.5, "material": "m", "flip_normals": %s})";
  char text[256];
  std::snprintf(text, sizeof text, shape, "false");
  const auto outward = load(text);
  std::snprintf(text, sizeof text, shape, "true");
  const auto inward = load(text);
  const Ray fromY{Vec3(0, 3, 1.5f), Vec3(0, -1, 0)};  // hits (0, 0.5, 1.5): φ = π/2, z/length = 0.75
  const std::optional<Hit> h = outward->accel->intersect(fromY), g = inward->accel->intersect(fromY);
  ASSERT_TRUE(h && g);
  const Vec2 uv = outward->uv(*h);
  EXPECT_NEAR(uv.x, 0.25f, 1e-6f);
  EXPECT_NEAR(uv.y, 0.25f, 1e-6f);  // Mitsuba's v = 0.75, counted from the image's top
  EXPECT_NEAR(h->ng.y, 1.0f, 1e-6f);
  EXPECT_NEAR(g->ng.y, -1.0f, 1e-6f);
  const std::optional<Hit> fromX = outward->accel->intersect(Ray{Vec3(-3, 0, 0.2f), Vec3(1, 0, 0)});  // φ = π
  ASSERT_TRUE(fromX);
  EXPECT_NEAR(outward->uv(*fromX).x, 0.5f, 1e-6f);
  EXPECT_NEAR(outward->uv(*fromX).y, 0.9f, 1e-6f);
}

TEST(Cylinder, UniformAreaSampling) {
  const auto scene = load(kTilted);
  const Shape& s = scene->shapes[0];
  const Local f;
  constexpr int kPhiCells = 8, kZCells = 5, kSamples = 40000;
  int counts[kPhiCells][kZCells] = {};
  Rng rng(3);
  for (int i = 0; i < kSamples; ++i) {
    const SurfaceSample x = s.sampleUniform(Vec2(rng.uniform(), rng.uniform()));
    EXPECT_NEAR(x.pdfArea, 1.0f / (2.0f * kPi * kRadius * kLength), 1e-6f);
    const glm::dvec3 p = f.of(glm::dvec3(x.p) - glm::dvec3(kP0));
    ASSERT_NEAR(std::hypot(p.x, p.y), kRadius, 1e-5);
    ASSERT_GE(p.z, -1e-5);
    ASSERT_LE(p.z, kLength + 1e-5);
    EXPECT_NEAR(glm::length(f.of(glm::dvec3(x.ng)) - glm::dvec3(p.x, p.y, 0.0) / double(kRadius)), 0.0, 1e-5);
    double phi = std::atan2(p.y, p.x);
    if (phi < 0.0) phi += 2.0 * M_PI;
    ++counts[std::min(int(phi / (2.0 * M_PI) * kPhiCells), kPhiCells - 1)][std::min(int(p.z / kLength * kZCells), kZCells - 1)];
  }
  // χ² over equal-area cells against uniform: 39 degrees of freedom, 99.9% quantile 72.1.
  const double expected = double(kSamples) / (kPhiCells * kZCells);
  double chi2 = 0.0;
  for (auto& row : counts)
    for (const int c : row) chi2 += (c - expected) * (c - expected) / expected;
  EXPECT_LT(chi2, 72.1);
}

TEST(Cylinder, PlacementAndErrors) {
  EXPECT_CONTAINS(loadError(R"({"type": "cylinder", "p0": [0, 0, 0], "p1": [0, 0, 1], "radius": 0, "material": "m"})"),
                  "cylinder.json: /shapes/0/radius: must be positive");
  EXPECT_CONTAINS(loadError(R"({"type": "cylinder", "p0": [1, 1, 1], "p1": [1, 1, 1], "radius": 1, "material": "m"})"),
                  "/shapes/0/p1: must differ from p0");
  // A non-uniform scale across the axis makes an elliptic tube.
  EXPECT_CONTAINS(loadError(R"({"type": "cylinder", "p0": [0, 0, 0], "p1": [0, 0, 1], "radius": 1, "material": "m",
                               "transform": [[2, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]]})"),
                  "/shapes/0/transform: does not keep the cylinder circular");
  EXPECT_CONTAINS(loadError(R"({"type": "cylinder", "p0": [0, 0, 0], "p1": [0, 0, 1], "radius": 1, "material": "m",
                               "transform": [[-1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]]})"),
                  "unmirrored");
  // Stretching along the axis and scaling uniformly are fine: radius 2·0.5, length 2·3·1.
  const auto stretched = load(R"({"type": "cylinder", "p0": [0, 0, 0], "p1": [0, 0, 1], "radius": 0.5, "material": "m",
                                  "transform": [[2, 0, 0, 1], [0, 2, 0, 0], [0, 0, 6, 0], [0, 0, 0, 1]]})");
  EXPECT_NEAR(stretched->shapes[0].cylinder.radius, 1.0f, 1e-6f);
  EXPECT_NEAR(stretched->shapes[0].cylinder.length, 6.0f, 1e-6f);
  EXPECT_NEAR(stretched->shapes[0].cylinder.base.x, 1.0f, 1e-6f);

  // Mitsuba: the documentation scene's cylinder, radius 0.5, rotated about z and lifted by 0.2.
  const std::string xml = R"(<scene version="3.0.0">
    <sensor type="perspective"><float name="fov" value="45"/><film type="hdrfilm"><integer name="width" value="4"/><integer name="height" value="4"/></film></sensor>
    <emitter type="point"><point name="position" x="0" y="0" z="3"/><spectrum name="intensity" value="1"/></emitter>
    <shape type="cylinder"><float name="radius" value="0.5"/>
      <transform name="to_world"><rotate z="1" angle="225"/><translate x="0" y="0" z="0.2"/></transform></shape>
    <shape type="cylinder"><point name="p0" x="1" y="0" z="0"/><point name="p1" x="1" y="3" z="0"/><boolean name="flip_normals" value="true"/></shape>
    </scene>)";
  const auto scene = loadSceneFromJson(mitsuba::translateMitsubaScene(xml, "c.xml").scene, "c.xml");
  const Cylinder& a = scene->shapes[0].cylinder;
  EXPECT_NEAR(glm::length(a.base - Vec3(0, 0, 0.2f)), 0.0f, 1e-6f);
  EXPECT_NEAR(a.radius, 0.5f, 1e-6f);
  EXPECT_NEAR(a.length, 1.0f, 1e-6f);
  EXPECT_NEAR(a.frame.n.z, 1.0f, 1e-6f);
  EXPECT_NEAR(glm::length(a.frame.s - Vec3(-1, -1, 0) / std::sqrt(2.0f)), 0.0f, 1e-6f);  // x rotated by 225°
  const Cylinder& b = scene->shapes[1].cylinder;
  EXPECT_NEAR(b.radius, 1.0f, 1e-6f);  // Mitsuba's default radius
  EXPECT_NEAR(b.length, 3.0f, 1e-6f);
  EXPECT_TRUE(b.inward);
}

}  // namespace
}  // namespace kasha
